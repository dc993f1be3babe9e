"""A page's shapes that are not sentences made plain clauses before reading, so the rest of
the reader sees running text (the shapes are data: ``page.json``): an e-mail thread oldest
first (the reply's corrections after what they correct; "X wrote:" lines go); a chat's or a
script's speaker labels; a dialogue's turns ("Robot: The phone? Me: leave it") as a question
and its answer; a question and its answer ("TV? A: Off", "The light? Off.") as one clause; a
shouted telegram ("MUG TO SINK STOP") in lower case with its words as punctuation; a
thread's post numbers ("2/ keys -> drawer 3/ ...") as sentence ends; a typing slip fixed in
place ("the male - sorry, MUG", "the sinking. Sink.") as the word meant; a bare heading ("-
fridge") as the place of its items' dangling "in"; config lines
(``soap_bar.home = drawer``) and code-like lines (``lamp.off()``, "lid ↓"); a report's
future ("will be in a cabinet") as the state asked for.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from functools import cache
from itertools import pairwise

from emboteam.pfg.offline import knowledge as kn
from emboteam.pfg.offline.morphology import edit_distance


class PageFile(kn.Strict):
    """``data/page.json``: the patterns of each shape and the words they turn on."""

    about: str = ""
    quote: str
    quote_header: str
    speaker: str
    speaker_lines: int
    turn: str
    turns_min: int
    asker_share: float
    shout_words: int
    shout_share: float
    telegram_min: int
    telegram: tuple[kn.Rewrite, ...]
    dropped_place: str
    post: str
    slip_cue: str
    slip_echo: str
    slip_back: int
    slip_edits: int
    question: str
    short_answer: int
    question_fillers: tuple[str, ...]
    question_words: tuple[str, ...]
    question_words_max: int
    wh: tuple[kn.Rewrite, ...]
    answer_pronouns: tuple[str, ...]
    answer_not_joined: tuple[str, ...]
    dangling: str
    pronoun_place: str
    config_line: str
    config_section: str
    config_comment: str
    config_lines: int
    place_keys: tuple[str, ...]
    not_keys: tuple[str, ...]
    parts: tuple[str, ...]
    code: tuple[kn.Rewrite, ...]
    future: tuple[kn.Rewrite, ...]


@cache
def _page() -> tuple[PageFile, dict[str, re.Pattern[str]], dict[str, tuple[kn.CompiledRewrite, ...]]]:
    data = kn.load("page.json", PageFile)
    names = ("quote", "quote_header", "speaker", "turn", "dropped_place", "post", "slip_cue", "slip_echo",
             "question", "dangling", "pronoun_place", "config_line", "config_section", "config_comment")
    rx = {n: re.compile(getattr(data, n), re.M if n == "question" else 0) for n in names}
    rx["filler"] = re.compile(r"^(?:" + "|".join(data.question_fillers) + r")\s+", re.I)
    rx["joined"] = re.compile(r"\0[ \t]*(?:" + "|".join(data.answer_pronouns) + r")\b[ \t]*", re.I)
    return data, rx, {n: kn.compile_rewrites(getattr(data, n)) for n in ("wh", "code", "future", "telegram")}


def warm_page() -> None:
    """Load and compile the page rules ahead of the first instruction."""
    _page()


def read_page(text: str, bare: Callable[[str], bool], noun: Callable[[str], bool],
              nounish: Callable[[str], bool], bullet: re.Pattern[str]) -> str:
    """The text with its page shapes as plain clauses. ``bare``: a phrase only names things;
    ``noun``: a word names a scene thing (a speaker's label does not); ``nounish``: a word
    may be a noun; ``bullet``: a list item's opening."""
    data, rx, rules = _page()

    def named(question: str) -> bool:    # "TV", "Spare loo roll", "The light": no question's words
        words = re.findall(r"[a-z']+", question.lower())
        return 0 < len(words) <= data.question_words_max and nounish(words[-1]) \
            and not any(w in data.question_words for w in words)

    text = _telegram(text, rx, data, rules["telegram"], noun)
    text = _slips(_posts(text, rx), rx, data, noun)
    text, turns = _turns(text, rx, data, noun)
    lines = _headings(_speakers(_thread(text.split("\n"), rx), rx, data, noun), rx, bare, bullet)
    out = kn.apply_rewrites(rules["code"], "\n".join(_config(lines, rx, data, noun)))
    out = rx["question"].sub(lambda m: _answered(m, data, named, bare), out)
    if turns:       # an answer not joined to its question stands on its own
        out = re.sub(r"\?[ \t]*A:[ \t]*", "? ", out)
    out = rx["joined"].sub("", out).replace("\0", "")     # the answer's "they" is the question's thing
    return kn.apply_rewrites(rules["future"], out)


def _telegram(text: str, rx: dict[str, re.Pattern[str]], data: PageFile,
              rules: tuple[kn.CompiledRewrite, ...], noun: Callable[[str], bool]) -> str:
    """A shouted text in lower case (capitals carry no names there); a telegram's words
    ("STOP", "NEGATIVE") as the punctuation and the no they stand for, and the "in" or "on" it
    drops ("APPLE REMAINS FRIDGE")."""
    words = re.findall(r"[A-Za-z]{2,}", text)
    if len(words) < data.shout_words or sum(w.isupper() for w in words) < data.shout_share * len(words):
        return text
    if len(re.findall(r"\bSTOP\b", text)) < data.telegram_min:
        return text.lower()
    out = kn.apply_rewrites(rules, text.lower())
    out = rx["dropped_place"].sub(lambda m: f"{m.group(1)} on {m.group(2)}" if noun(m.group(2)) else m.group(0), out)
    return ". ".join(_name_run(x.split(), noun) for x in out.split(". "))


def _posts(text: str, rx: dict[str, re.Pattern[str]]) -> str:
    """A thread's posts numbered in order ("1/ ... 2/ ...", "2/4 ... 3/4 ..."): each number
    ends the post before it, as a full stop would (numbers out of order are no thread)."""
    found = list(rx["post"].finditer(text))
    numbers = [int(m.group(1)) for m in found]
    if len(found) < 2 or any(b != a + 1 for a, b in pairwise(numbers)):
        return text
    for m in found[::-1]:
        before = text[:m.start()].rstrip()
        text = before + ("" if not before or before[-1] in ".!?" else ".") + " " + text[m.end():]
    return text.lstrip()


_WORD = re.compile(r"[A-Za-z]+")


def _slips(text: str, rx: dict[str, re.Pattern[str]], data: PageFile, noun: Callable[[str], bool]) -> str:
    """A typing slip the writer fixes at once, as the word meant: "the male in the microwave -
    sorry, MUG" (a named thing after the cue replaces the nearest word before it that begins
    like it and names nothing) and "into the sinking. Sink." (a one-word sentence, a name or
    shouted, echoing the word before it a few letters off; not an inflection: "confirm.
    Confirmed.")."""
    edits: list[tuple[int, int, str]] = []
    for m in rx["slip_cue"].finditer(text):
        meant = m.group(1).lower()
        if not noun(meant) or (edits and m.start() < edits[-1][1]):
            continue
        words = _WORD.finditer(text, edits[-1][1] if edits else 0, m.start())
        for w in list(words)[::-1][:data.slip_back]:
            said = w.group(0).lower()
            if said[0] == meant[0] and said != meant and len(said) > 2 and not noun(said):
                cut = "" if text[m.end():m.end() + 1] in ",.;:!?" else ", "
                edits += [(w.start(), w.end(), meant), (m.start(), m.end(), cut)]
                break
    for start, end, said in edits[::-1]:
        text = text[:start] + said + text[end:]

    def echo(m: re.Match[str]) -> str:
        said, meant = m.group(1).lower(), m.group(3).lower()     # a name, or a word shouted
        near = said.startswith(meant) or edit_distance(said, meant) <= data.slip_edits
        if said[0] != meant[0] or said == meant or noun(said) or not near or not (noun(meant) or m.group(3).isupper()):
            return m.group(0)
        return meant + m.group(4)
    return rx["slip_echo"].sub(echo, text)


def _name_run(words: list[str], noun: Callable[[str], bool]) -> str:
    """A telegram sentence's run of names as a list ("CARD PHONE KEYS INTO BOX"): a name said
    twice starts a new sentence ("... DRAWER DRAWER SHUT"), and a run that ends its clause
    with no verb names its place last ("CD PEN PENCIL DRAWER")."""
    def name(said: str) -> bool:
        return said.replace(" ", "").isalpha() and noun(said)
    units: list[str] = []
    while words:
        step = 2 if len(words) > 1 and name(" ".join(words[:2])) else 1    # "soap bar"
        units.append(" ".join(words[:step]))
        words = words[step:]
    runs: list[list[str]] = []          # names in a row, or one other word
    for k, said in enumerate(units):
        if k and name(said) and name(units[k - 1]) and said != runs[-1][-1]:
            runs[-1].append(said)
        else:
            runs.append([said])
    out: list[str] = []
    for k, run in enumerate(runs):
        after = runs[k + 1][0] if k + 1 < len(runs) else ""
        placed = len(run) > 1 and (not after or after.endswith(",") or after == run[-1])
        said = ", ".join(run[:-1]) + (" → " if placed else ", ") + run[-1] if len(run) > 1 else run[0]
        out.append(said + ("." if after == run[-1] else ""))
    return " ".join(out)


def _turns(text: str, rx: dict[str, re.Pattern[str]], data: PageFile,
           noun: Callable[[str], bool]) -> tuple[str, bool]:
    """A dialogue of two speakers, one asking, as questions and answers ("Robot: The phone?
    Me: not my phone" is "The phone? A: not my phone"): the thing asked about is what the
    answer is about, and the asker's own sentences are no requests. Whether one was found."""
    found = [m for m in rx["turn"].finditer(text) if not any(noun(w.lower()) for w in m.group(1).split())]
    labels = [m.group(1).lower() for m in found]
    if len(found) < data.turns_min or len(set(labels)) != 2 or set(labels) == {"q", "a"}:
        return text, False
    ends = [m.start() for m in found[1:]] + [len(text)]
    bodies = [text[m.end():e].strip() for m, e in zip(found, ends, strict=True)]
    share = {x: sum(b.endswith("?") for y, b in zip(labels, bodies, strict=True) if y == x) / labels.count(x)
             for x in set(labels)}
    asker = max(share, key=lambda x: share[x])
    if share[asker] < data.asker_share or min(share.values()) > 1 - data.asker_share:
        return text, False
    out, asked = [text[:found[0].start()].strip()], False
    for label, body in zip(labels, bodies, strict=True):
        if label == asker:      # only its question: what the next answer is about
            asked = body.endswith("?")
            out.append(re.split(r"(?<=[.!?])\s+", body)[-1] if asked else "")
        else:
            out.append(("A: " if asked else "") + body + ("" if body[-1:] in ".!?" else "."))
            asked = False
    return " ".join(x for x in out if x), True


def _thread(lines: list[str], rx: dict[str, re.Pattern[str]]) -> list[str]:
    """An e-mail thread in the order it was written: the most quoted message first."""
    depth = [len(re.sub(r"[^>]", "", m.group(1))) if (m := rx["quote"].match(x)) else 0 for x in lines]
    if not any(depth):
        return lines
    bodies = [rx["quote"].sub("", x) for x in lines]
    return [b for d in sorted(set(depth), reverse=True) for b, k in zip(bodies, depth, strict=True)
            if k == d and not rx["quote_header"].match(b) and b.strip()]


def _speakers(lines: list[str], rx: dict[str, re.Pattern[str]], data: PageFile,
              noun: Callable[[str], bool]) -> list[str]:
    """A chat log's or a script's lines without who says them (a label that names no
    thing, on at least ``speaker_lines`` lines)."""
    def who(line: str) -> bool:
        m = rx["speaker"].match(line)
        return m is not None and m.group(1).upper() not in {"Q", "A"} and not any(noun(w.lower()) for w in m.group(1).split())
    if sum(map(who, lines)) < data.speaker_lines:
        return lines
    return [rx["speaker"].sub("", x, count=1) if who(x) else x for x in lines]


def _headings(lines: list[str], rx: dict[str, re.Pattern[str]], bare: Callable[[str], bool],
              bullet: re.Pattern[str]) -> list[str]:
    """Items indented under a bare heading ("- fridge"): their dangling "in" and "next to
    it" are the heading's place."""
    out: list[str] = []
    head, level = "", -1
    for line in lines:
        indent = len(line) - len(line.lstrip(" \t"))
        item = bullet.sub("", line).strip()
        if indent <= level or not line.strip():
            head, level = "", -1
        if head:
            line = rx["pronoun_place"].sub(rf"\1 the {head}", rx["dangling"].sub(rf"\1 the {head}", line))
        elif bullet.match(line) and item and not item.endswith(":") and bare(item):
            head, level = re.sub(r"^(?:the|a|an) ", "", item.lower()), indent
        out.append(line)
    return out


def _config(lines: list[str], rx: dict[str, re.Pattern[str]], data: PageFile,
            noun: Callable[[str], bool]) -> list[str]:
    """A config file's ``key = value`` lines as clauses: a place key's value is where the
    thing goes ("soap bar → drawer"); a section names the owner of a part ("[shower]" over
    "door = open") or the kind of an adjective ("[lights]" over "main = off")."""
    if sum(bool(rx["config_line"].match(rx["config_comment"].sub("", x))) for x in lines) < data.config_lines:
        return lines
    out: list[str] = []
    section = ""
    for line in lines:
        if m := rx["config_section"].match(line):
            section = m.group(1).strip().lower()
            continue
        comment = rx["config_comment"].search(line)
        if (m := rx["config_line"].match(rx["config_comment"].sub("", line))) is None:
            out.append(line)
            continue
        *thing, key = m.group(1).lower().split(".")
        value = m.group(2).replace("_", " ")
        if not thing:
            thing, key = [key], ""
        name = " ".join(thing).replace("_", " ")
        if section and " " not in name and noun(section.split()[-1]):   # "shower door", "main lights"
            name = f"{section} {name}" if name in data.parts else f"{name} {section}"
        said = (f"{name} → {value}" if key in data.place_keys else f"{name} not in the {value}"
                if key in data.not_keys else f"{name} {value}")
        out.append(said + (f" ({comment.group(1)})" if comment and comment.group(1) else "") + ".")
    return out


def _answered(m: re.Match[str], data: PageFile, named: Callable[[str], bool], bare: Callable[[str], bool]) -> str:
    """A question and the start of its answer as one clause's start, or as written when the
    question is no thing's name or the answer has its own subject; a marked answer that only
    names a thing ("Spoons? A: a drawer, then close it") is where the thing asked goes."""
    lead, question, marked = m.group(1), m.group(2).strip(), m.group(3)
    rest = m.string[m.end():]
    answer = re.split(r"[.;!?\n]", rest, maxsplit=1)[0].split()
    if not answer or (not marked and len(answer) > data.short_answer):
        return m.group(0)
    question = _page()[1]["filler"].sub("", question)      # "And the statue?"
    asked = kn.apply_rewrites(_page()[2]["wh"], question)
    if asked == question and not named(question):
        return m.group(0)
    first = answer[0].lower().strip(",")
    if marked and bare(re.split(r"[,;.!?\n]", rest, maxsplit=1)[0].strip()):
        return f"{lead}{asked} → "
    if first in data.answer_not_joined:
        return m.group(0)
    if first in data.answer_pronouns:     # "The soap? A: They stay on the shelf"
        return f"{lead}{asked} \0"
    return f"{lead}{asked} "
