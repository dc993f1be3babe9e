"""The surface of an instruction, made into the reader's usual input: speech-to-text
transcripts, text messages and non-native calques.

Before the reader normalises the text (:mod:`.text`), the rules of ``data/surface.json``
rewrite what people type or dictate: texting abbreviations ("b4", "2 the stove"),
homophones ("a draw" when the scene has a drawer, "sell fone"), misheard function words
("switch the lamp of", "turn it on to", "end" for "and"), split words checked against
the scene's object names ("micro wave", "news paper", "so far"), non-native calques ("make
it to burn", "the curtain of the shower") and the clause breaks an unpunctuated transcript
leaves out. A rewrite is either *certain* (a symbol, a word that is no English, a cue the
scene settles) and made on the text that is read, or a guess (a misheard "in" may be a real
"in", "the apple of the sink" may be a compound) made only on an *alternative* text, which
the front end reads beside it and offers as a point of doubt of kind ``surface``
(:func:`surface_doubt`), priced by ``doubts/priors.json``.

Kept by hand (regular expressions and a few word tests against the lexicon): the rules are
small, closed and must know the lexicon and the scene; a speech or texting normaliser
library would know neither and add a dependency.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass
from functools import cache

from pydantic import Field

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.foreign import translate, warm_foreign
from emboteam.pfg.offline.knowledge import Rewrite, Strict, load
from emboteam.pfg.offline.layout import Layout, Words, read_layout
from emboteam.pfg.offline.morphology import edit_distance, singular, verb_lemma
from emboteam.pfg.offline.page import read_page
from emboteam.pfg.offline.regex_filter import needle_groups
from emboteam.pfg.offline.text import fold_accents, split_camel
from emboteam.world.goals import Condition

KIND = "surface"


class SurfaceRewrite(Rewrite):
    """A rewrite of the text as typed, of a kind; certain or a guess; for scenes with one
    of ``needs`` (any scene when empty)."""

    kind: str
    certain: bool = True
    needs: tuple[str, ...] = ()


class Transcript(Strict):
    """When an unpunctuated text is a transcript and where its clauses start."""

    min_words: int = Field(12, ge=3)
    #: "the potato goes in ...": a noun phrase before one of these starts a clause
    clause_verbs: tuple[str, ...]
    #: a verb after one of these continues the clause ("can you put", "to boil")
    no_break_after: tuple[str, ...]
    #: words that may end a clause besides nouns, pronouns and states ("leave it there",
    #: "the paper in the bin is fine", "the soap in the sink please")
    phrase_ends: tuple[str, ...] = ()


class Calque(Strict):
    """"the N of the M": heads that are parts, portions or amounts, no calque."""

    not_heads: tuple[str, ...]
    place_preposition: str = "in"


class RealWords(Strict):
    """A real English word that a voice keyboard or autocorrect put for a scene thing ("the
    pit stays on the stove"): after one of ``after``, heading its noun phrase, unknown to the
    lexicon, and sounding like the name of one scene type but for its ``vowels``."""

    after: tuple[str, ...]
    vowels: str = "aeiou"


class SurfaceFile(Strict):
    """``data/surface.json``."""

    about: str = ""
    rewrites: tuple[SurfaceRewrite, ...]
    and_sounds: tuple[str, ...]
    transcript: Transcript
    calque: Calque
    real_words: RealWords
    layout: Layout


#: the kind of guess that names an alternative text for the priors, when several fired:
#: the one that changes the reading most (a transcript's clause breaks) first
_LABEL_ORDER = ("clause_breaks", "transcript", "sound_join", "calque", "and_heard", "real_word")


@dataclass(frozen=True)
class Surface:
    """The text to read (the certain rewrites made), the alternative text (the guesses
    made too; None when there is none) and the kinds of rewrite that fired in each."""

    text: str
    alternative: str | None = None
    kinds: tuple[str, ...] = ()
    guesses: tuple[str, ...] = ()

    @property
    def label(self) -> str:
        """The alternative's label for the priors (``surface`` in ``priors.json``)."""
        return min(self.guesses, key=lambda g: _LABEL_ORDER.index(g) if g in _LABEL_ORDER else len(_LABEL_ORDER))


@cache
def _data() -> tuple[SurfaceFile, tuple[tuple[re.Pattern[str], SurfaceRewrite, tuple[frozenset[str], ...]], ...]]:
    data = load("surface.json", SurfaceFile)
    compiled = [(re.compile(r.pattern, re.IGNORECASE), r) for r in data.rewrites]
    # lower-case strings a match has one of each group of in an ASCII text (:mod:`.regex_filter`)
    return data, tuple((pattern, r, needle_groups(pattern)) for pattern, r in compiled)


def _rewrite(text: str, scene_types: Collection[str], certain: bool, kinds: list[str]) -> str:
    """The rules of one certainty, in order; the kinds that changed the text noted. A rule
    that misses a needle group in an ASCII text cannot match it and is skipped (most texts
    match no rule: the reader's time budget)."""
    lower = text.lower() if text.isascii() else None
    for pattern, rule, required in _data()[1]:
        if rule.certain != certain or (rule.needs and not any(t in scene_types for t in rule.needs)):
            continue
        if lower is not None and required:
            missing = False
            for group in required:      # loops, not a call or any(): this runs per rule
                for needle in group:
                    if needle in lower:
                        break
                else:
                    missing = True
                    break
            if missing:
                continue
        new = pattern.sub(rule.replace, text)
        if new != text:
            kinds.append(rule.kind)
            text = new
            lower = text.lower() if text.isascii() else None
    return text


# -- words: what a word is to the reader --------------------------------------------------

_PARTS = re.compile(r"\s+|[A-Za-z0-9']+|[^\sA-Za-z0-9']+")


def _parts(text: str) -> tuple[list[str], list[int]]:
    """The text cut losslessly into spaces, words and runs of symbols, and where the
    non-space parts are: a pass edits words (same count: a word it drops becomes "") and
    the rest of the text stays as typed."""
    parts = _PARTS.findall(text)
    return parts, [i for i, p in enumerate(parts) if not p.isspace()]


def _words(text: str) -> list[str]:
    parts, at = _parts(text)
    return [parts[i] for i in at]


def _with_words(text: str, words: list[str]) -> str:
    parts, at = _parts(text)
    for i, w in zip(at, words, strict=True):
        parts[i] = w
    return "".join(parts)


@cache
def _is_noun(word: str) -> bool:
    # remembered per word (the lexicon is fixed at import): asked of every run of words
    return singular(word.lower(), lx.nouns())[0] in lx.nouns()


@cache
def _nounish(word: str) -> bool:
    """A noun, or a word of a noun phrase ("door" of "shower door")."""
    return _is_noun(word) or (word.lower() in lx.noun_words() and not _closed(word))


def _is_verb(word: str) -> bool:
    found = verb_lemma(word.lower())
    return found is not None and found[1] == "base"


@cache
def _closed_words() -> frozenset[str]:
    """Function words: never part of a misheard name ("off ty" is no "post")."""
    preps = {w for p in lx.PREPOSITIONS for w in p.split()}
    return frozenset(lx.DETERMINERS | lx.PARTICLES | lx.PRONOUNS | lx.COPULAS | preps
                     | {"and", "or", "but", "then", "to", "of", "so"})


def _closed(word: str) -> bool:
    return word.lower() in _closed_words()


def _says_what(cell: str) -> bool:
    """Whether a list's cell says what to do in its own words: a verb or a state first
    ("stays on the counter", "off"), not a thing or a place ("the cabinet")."""
    first = next(iter(re.findall(r"[a-z]+", cell.lower())), "")
    return first in lx.STATES or (verb_lemma(first) is not None and not _is_noun(first))


def _bare(item: str) -> bool:
    """Whether a list item only names things ("the card", "both keys")."""
    words = re.findall(r"[a-z]+", item.lower())
    return bool(words) and all(w in lx.DETERMINERS or w in lx.QUANTIFIERS or w in lx.NUMBERS
                               or w in {"and", "or"} or (_nounish(w) and not _is_verb(w)) for w in words)


def _a_place(heading: str) -> bool:
    """Whether a list's heading is a place ("into the box:", "on the counter:")."""
    first = next(iter(re.findall(r"[a-z]+", heading.lower())), "")
    return any(p.split()[0] == first for p in lx.PREPOSITIONS)


_LIST_WORDS = Words(_says_what, _bare, _a_place)


def _opens_phrase(word: str) -> bool:
    w = word.lower()
    return w in lx.DETERMINERS or w in lx.PRONOUNS or w in {"i", "you", "then", "also", "please"} or _is_verb(w)


# -- "and" heard as "an", "end", "in" ----------------------------------------------------

def _and_sounds(words: list[str], sounds: Collection[str]) -> list[str]:
    """A word that sounds like "and", not after a determiner, before a determiner, a
    pronoun or a verb, is "and" ("switch it on end the potato goes ...")."""
    out = list(words)
    for k in range(1, len(words) - 1):
        w = words[k].lower()
        vowel_next = w == "an" and words[k + 1][:1].lower() in "aeiou"     # "an empty room"
        if w in sounds and words[k - 1].lower() not in lx.DETERMINERS and _opens_phrase(words[k + 1]) \
                and words[k - 1].isalpha() and not vowel_next:
            out[k] = "and"
    return out


def _in_as_and(words: list[str]) -> list[str]:
    """A second "in the X" right after a place ("in the draw in the key chain to", "on the
    coffee table in the news paper on the sofa stays"): more likely "and" in a transcript."""
    out = list(words)
    for k in range(3, len(words) - 1):
        if words[k].lower() != "in" or words[k + 1].lower() not in lx.DETERMINERS:
            continue
        back = [w.lower() for w in words[max(0, k - 4):k]]
        if any(p in back[:-1] for p in ("in", "on", "into", "onto")) and _is_noun(words[k - 1]):
            out[k] = "and"
    return out


# -- split and run-together names, against the scene ---------------------------------------

@cache
def _joined_names() -> dict[str, tuple[tuple[str, frozenset[str]], ...]]:
    """Every noun phrase run together -> (the phrase, the types it names): "newspaper",
    "remotecontrol" -> "remote control". Built once; a scene only filters it."""
    out: dict[str, list[tuple[str, frozenset[str]]]] = {}
    for phrase, concept in lx.nouns().items():
        out.setdefault(phrase.replace(" ", ""), []).append((phrase, frozenset((*concept.types, *concept.fallback))))
    return {k: tuple(v) for k, v in out.items()}


def _scene_name(joined: str, scene_types: frozenset[str]) -> str | None:
    """The noun phrase that, run together, is ``joined`` and names a type of the scene."""
    named = _joined_names().get(joined)
    return None if named is None else next((p for p, types in named if types & scene_types), None)


def _sounds_like(joined: str, scene_types: frozenset[str]) -> str | None:
    from emboteam.pfg.offline.doubts.sound_alike import _closest, sound

    said = sound(joined)
    types = _closest(said, scene_types)
    if types is None:
        return None
    names = _named_sounds(types[0])
    return min(names, key=lambda ps: (edit_distance(ps[1], said, 4), ps[0]))[0] if names else None


@cache
def _named_sounds(type_: str) -> tuple[tuple[str, str], ...]:
    """(phrase, sound) of each noun phrase of the lexicon whose first type is ``type_``: the
    same for every instruction (the lexicon is fixed at import), so worked out once."""
    from emboteam.pfg.offline.doubts.sound_alike import sound

    return tuple((p, sound(p)) for p, c in lx.nouns().items() if c.types and c.types[0] == type_)


def _split_words(words: list[str], scene_types: frozenset[str], guess: bool) -> list[str]:
    """Two or three words that run together into a scene thing's name ("micro wave",
    "tele vision", "remote con troll") are that name: for certain when the run names it
    exactly and its first word names nothing, as a guess when it only sounds like it ("so
    far", "to motto", "hold her"). The words after the first of a run become ""."""
    out = list(words)
    alpha = [w.isalpha() for w in words]
    k = 0
    while k < len(words):
        name, n = _run_name(words, alpha, k, scene_types, guess)
        if name is not None:
            out[k:k + n] = [name] + [""] * (n - 1)
        k += n
    return out


def _run_name(words: list[str], alpha: list[bool], k: int, scene_types: frozenset[str],
              guess: bool) -> tuple[str | None, int]:
    """The scene name the run of words from ``k`` says, and the run's length (1: none);
    ``alpha``: whether each word is letters only."""
    for n in (3, 2):
        if k + n > len(words) or not all(alpha[k:k + n]):
            continue
        run = words[k:k + n]
        joined = "".join(run).lower()
        exact = _scene_name(joined, scene_types) or \
            (_scene_name(joined[:-1], scene_types) if joined.endswith("s") else None)
        if exact and not _is_noun(run[0]) and not _is_noun(" ".join(run).lower()):
            return exact, n
        after_det = k > 0 and words[k - 1].lower() in lx.DETERMINERS
        if guess and len(joined) >= 5 and _may_mishear(run, after_det):
            heard = _sounds_like(joined, scene_types)
            if heard:
                return heard, n
    return None, 1


def _may_mishear(run: list[str], after_det: bool) -> bool:
    """Whether a run of words may be a misheard name: no noun ends it and it is no noun
    phrase; after a determiner, where no function word or verb can stand ("the to motto",
    "on the hold her"), any run of words that name nothing; elsewhere only one with a word the lexicon does not
    know and no function word or later verb in it ("the dish sponje")."""
    if _is_noun(run[-1]) or _is_noun(" ".join(run).lower()):
        return False
    if after_det and not any(_nounish(w) for w in run):
        return True
    vocabulary = lx.vocabulary()
    return any(w.lower() not in vocabulary for w in run) and not any(_closed(w) for w in run) \
        and not any(verb_lemma(w.lower()) for w in run[1:])


# -- real words for scene things ("the pit" for the pot) ------------------------------------

def _real_words(words: list[str], scene_types: frozenset[str]) -> list[str]:
    """A real English word in a thing's slot that names nothing and sounds like one scene
    thing but for a vowel ("the cattle", "the sunk") is that thing: a guess (the alternative
    text), since it may mean what it says. A word the lexicon knows, a modifier ("the top
    shelf") and a non-word (the spelling corrector's) are left alone."""
    from emboteam.pfg.offline.morphology import is_english_word

    rule = _data()[0].real_words
    out = list(words)
    for k in range(1, len(words)):
        w = words[k].lower()
        if words[k - 1].lower() not in rule.after or not w.isalpha() or w in lx.vocabulary() or _nounish(w):
            continue
        if k + 1 < len(words) and _nounish(words[k + 1]):
            continue
        name = _vowel_slip(w, scene_types, rule.vowels)
        if name is not None and is_english_word(w):
            out[k] = name
    return out


def _vowel_slip(word: str, scene_types: frozenset[str], vowels: str) -> str | None:
    """The one scene thing's name that sounds like ``word`` but for its vowels, or None
    (none, or several types: no guess)."""
    from emboteam.pfg.offline.doubts.sound_alike import _sounds, sound

    said = sound(word)
    found = {types[0]: s for s, types in _sounds(scene_types).get(said[:1], ())
             if len(s) == len(said) and s != said
             and all(a == b or (a in vowels and b in vowels) for a, b in zip(s, said, strict=True))}
    if len(found) != 1:
        return None
    (type_, heard), = found.items()
    return next((p for p, ps in _named_sounds(type_) if ps == heard), None)


# -- "the N of the M" --------------------------------------------------------------------

_OF = re.compile(r"\b(the|a|an|its|my|your) +([a-z]+) +of +(the +|its +|a +)?([a-z]+)\b", re.IGNORECASE)


def _calques(text: str, scene_types: frozenset[str], guess: bool) -> str:
    """"the curtain of the shower": the shower curtain when that names a scene type (for
    certain); "the apple of the sink", both things of the scene, as a guess: the apple in the
    sink."""
    calque = _data()[0].calque

    def named(words: str) -> bool:
        return _scene_name(words.replace(" ", ""), scene_types) is not None

    def one(m: re.Match[str]) -> str:
        det, head, of_det, owner = m.group(1), m.group(2).lower(), m.group(3), m.group(4).lower()
        if head in calque.not_heads or head in lx.MEASURE_WORDS:
            return m.group(0)
        owner_one = singular(owner, lx.nouns())[0]
        for front in dict.fromkeys((owner_one, owner)):
            compound = f"{front} {head}"
            if compound in lx.nouns() and named(compound) and (of_det or not _is_noun(owner)):
                return f"{det} {compound}"
        if guess and of_det and named(head) and named(owner_one) and head != owner_one:
            return f"{det} {head} {calque.place_preposition} {of_det}{owner}"
        return m.group(0)

    return _OF.sub(one, text)


# -- unpunctuated transcripts: where clauses start ------------------------------------------

def _clause_starts(words: list[str]) -> list[str]:
    """Commas where an unpunctuated transcript starts a new clause: before an imperative
    verb after a finished phrase that has its own verb ("grab the mug put it in"; not "desk
    lamp turn off", an object said first), before "(and) the X goes/stays". In a transcript
    that says its objects first ("desk lamp turn off the cloth throw in trash"), the break
    goes before the next object, not before its verb."""
    tr = _data()[0].transcript
    out = list(words)
    has_verb = False
    object_first = bool(words) and not _is_verb(words[0]) and \
        (_nounish(words[0]) or words[0].lower() in lx.DETERMINERS)
    for k in range(1, len(words)):
        w, prev = words[k], words[k - 1].lower()
        has_verb = has_verb or _is_verb(prev)
        if not prev.isalpha() or not w.isalpha():
            continue
        if prev in {"and", "then"} and k > 1 and w.lower() in lx.DETERMINERS \
                and _ended(words[k - 2].lower(), tr.phrase_ends) and _subject_then_verb(words, k, tr.clause_verbs):
            out[k - 1] = ", " + words[k - 1]       # "... on the coffee table and the paper on the sofa stays"
            has_verb = False
        elif prev not in tr.no_break_after and _ended(prev, tr.phrase_ends) \
                and _starts_clause(words, k, tr.clause_verbs, has_verb):
            at = _object_start(words, k) if object_first and _is_verb(w) else k
            out[at] = ", " + out[at]
            has_verb = False
    return out


def _object_start(words: list[str], k: int) -> int:
    """Where the object said before the verb at ``k`` starts ("the cloth throw": at "the";
    "and watch put": at "and")."""
    at = k
    while at > 1 and (_nounish(words[at - 1]) or words[at - 1].lower() in lx.DETERMINERS
                      or (words[at - 1].lower() == "of" and _nounish(words[at - 2]))):    # "the light of kitchen"
        at -= 1
    return at - 1 if at > 1 and words[at - 1].lower() in {"and", "then"} else at


def _ended(word: str, phrase_ends: Collection[str]) -> bool:
    """Whether a phrase can end with ``word``: a noun, a pronoun, a state, a particle
    ("switch it on put ..."), one of ``phrase_ends``."""
    if word in lx.DETERMINERS:
        return False
    return _is_noun(word) or word in lx.PRONOUNS or word in phrase_ends or word in lx.PARTICLES or word in lx.STATES


def _starts_clause(words: list[str], k: int, clause_verbs: Collection[str], has_verb: bool) -> bool:
    """An imperative verb with its object ("put it", "turn on the") after a clause with a
    verb, or "the X goes"."""
    w, prev = words[k].lower(), words[k - 1].lower()
    after = words[k + 1].lower() if k + 1 < len(words) else ""
    if _is_verb(w) and not _is_noun(w) and not (w in lx.STATES and _is_noun(prev)):     # "the curtains open"
        return has_verb and (after in lx.DETERMINERS or after in lx.PRONOUNS or after in lx.PARTICLES)
    preps = {x for p in lx.PREPOSITIONS for x in p.split()}
    # "the lettuce that is in the sink": a relative clause, no new one
    return w in lx.DETERMINERS and w not in {"that", "which"} and prev not in preps \
        and _subject_then_verb(words, k, clause_verbs)


def _subject_then_verb(words: list[str], k: int, verbs: Collection[str]) -> bool:
    """"the X (on the Y) goes ...": a noun phrase from ``k`` followed by a clause verb."""
    for j in range(k + 2, min(k + 8, len(words))):
        if _nounish(words[j - 1]) and (words[j].lower() in verbs or (_is_verb(words[j]) and not _is_noun(words[j])
                                       and j + 1 < len(words) and words[j + 1].lower() in {"it", "them"})):
            return True     # "the X goes ...", "the shower door close it"
        if not words[j - 1].isalpha() or (_is_verb(words[j - 1]) and not _is_noun(words[j - 1])):
            return False
    return False


def _unpunctuated(text: str) -> bool:
    return not re.search(r"[.,;:!?]", text)


def _transcript(text: str) -> bool:
    """An unpunctuated text long enough to hold several clauses: a speech-to-text transcript."""
    return _unpunctuated(text) and len(text.split()) >= _data()[0].transcript.min_words


def warm_surface() -> None:
    """Load the rules and index the names ahead of the first instruction."""
    _data()
    _joined_names()
    _closed_words()
    warm_foreign()


def read_surface(text: str, scene_types: Iterable[str]) -> Surface:
    """The text with its certain rewrites made and, when a guess applies, the alternative."""
    types = frozenset(scene_types)
    data = _data()[0]
    kinds: list[str] = []
    text = fold_accents(text)
    paged = read_page(text, _bare, _is_noun, _nounish, re.compile(data.layout.bullet))
    if paged != text:
        kinds.append("page")
        text = paged
    laid = read_layout(text, data.layout, _LIST_WORDS)
    if laid != text:
        kinds.append("layout")
        text = laid
    transcript = _transcript(text)
    said = split_camel(_rewrite(text, types, True, kinds))
    words = _words(said)
    english = translate(words)     # household words of other languages (foreign.py)
    if english != words:
        kinds.append("foreign")
        said, words = _with_words(said, english), _words(_with_words(said, english))
    fixed = _split_words(_and_sounds(words, data.and_sounds), types, guess=False)
    if fixed != words:
        kinds.append("spoken")
        said = _with_words(said, fixed)
    certain = _calques(said, types, guess=False)
    if certain != said:
        kinds.append("calque")
    guesses: list[str] = []
    alt = _rewrite(certain, types, False, guesses)
    # a misheard "in" is speech-to-text's: only in a text without punctuation
    for kind, step in (("and_heard", _in_as_and if _unpunctuated(text) else None),
                       ("sound_join", lambda w: _split_words(w, types, guess=True)),
                       ("clause_breaks", _clause_starts if transcript else None),
                       ("real_word", lambda w: _real_words(w, types))):
        if step is None:
            continue
        words = _words(alt)
        changed = step(words)
        if changed != words:
            guesses.append(kind)
            alt = _with_words(alt, changed)
    alternative = _calques(alt, types, guess=True)
    if alternative != alt:
        guesses.append("calque")
    text_out = certain if kinds else text
    return Surface(text_out, alternative if guesses and alternative != text_out else None,
                   tuple(dict.fromkeys(kinds)), tuple(dict.fromkeys(guesses)))


def surface_doubts(goals: tuple[Condition, ...], alternatives: Sequence[tuple[str, str, tuple[Condition, ...]]],
                   kind: str = KIND) -> list[Doubt]:
    """A point of doubt of kind ``surface`` per alternative text whose reading differs:
    the reading as said, or the reading of the text with the guesses made (``label`` the
    kinds of guess, ``how`` the text). Also the other readings of a self-correction
    (``kind`` ``correction``: :mod:`..corrections`)."""
    return [Doubt(kind, how, (Choice(AS_READ, "as said"), Choice(label, f"read as {how!r}", drop=goals, add=alt)))
            for label, how, alt in alternatives if alt and set(alt) != set(goals)]
