"""Passes over the parsed clauses of one instruction, before their semantics: what one
clause means depends on its neighbours. A state under "if" is a condition; "when I get
home" is a time; a place before a colon labels the objects after it; a verb without an
object shares the next one's; a participle, a purpose infinitive or "again" finishes the
act before it; a question pointing at an object, a guess where it is and small talk ask
for nothing.
"""

from __future__ import annotations

from dataclasses import replace

from emboteam.pfg.offline import lexicon, phrases
from emboteam.pfg.offline.clauses import AND, THEN, Clause
from emboteam.pfg.offline.cues import is_statement
from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words
from emboteam.pfg.offline.frames import parse_clause
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.phrases import Frame, Head, ParsedClause, Target, np_list, np_start, parse_np
from emboteam.pfg.offline.tagger import Item


def known_objects(items: list[Item]) -> list[Head] | None:
    """The noun phrases of a clause that is only noun phrases of known words ("the
    bread", "then the tomato"; not "wibble the tomato"), else None."""
    words = [i for i in items if i.punct is None]
    if not all(i.noun is not None or i.det or i.quant is not None or i.pron
               or i.number is not None or i.text in lexicon.COMMON_WORDS for i in words):
        return None
    # commas stay: they separate the phrases of a list ("keys, watch and the card")
    return np_list([i for i in items if i.punct in (None, ",")]) or np_list(words)


#: acts that ask for nothing on their own ("I'd love it if ...", "when I get home")
_NO_REQUEST = frozenset({None, lexicon.Act.CAUSE, lexicon.Act.GO, lexicon.Act.MAKE})
_W = word_tables("clause_passes")
_SHE_NEEDS_IT, _REQUEST_AFTER_IF, _REPORTED, _OWN_FUTURE = (pattern_tables("clause_passes").pattern(name) for name in (
    "she_needs_it", "request_after_if", "reported", "own_future"))
#: a person's own doings under "when", "before", "if": "when I get home", "before you go"
#: are a time, not a request
_PERSON = _W.set("person")


#: verbs of a question that points something out ("see the box on the table?")
_POINTING = _W.set("pointing")


#: acts a purpose infinitive asks of what was just placed ("put it on the hob to boil")
_PURPOSE_ACTS = frozenset({lexicon.Act.HEAT, lexicon.Act.COOK, lexicon.Act.COOL, lexicon.Act.CLEAN,
                           lexicon.Act.MICROWAVE, lexicon.Act.TOAST})


def purpose_acts(clause: Clause, parsed: ParsedClause) -> None:
    """"put the kettle on the hob to boil", "pop the wine in the fridge to chill": the
    placement is for the act after "to", which is asked of the same objects."""
    items = clause.items
    placing = [f for f in parsed.frames if f.act in (lexicon.Act.PLACE, lexicon.Act.GO)]
    if not placing:
        return
    for k in range(len(items) - 1):
        verb = items[k + 1].verb
        if items[k].text == "to" and verb is not None and verb.sense.act in _PURPOSE_ACTS \
                and items[k + 1].noun is None and (k + 2 >= len(items) or not np_start(items[k + 2])
                                                   or items[k + 2].pron in ("it", "them")):
            heads = [t.head for f in placing for t in f.targets]
            parsed.frames.append(Frame(verb.sense.act, verb.lemma, [Target(h) for h in heads],
                                       text=clause.text))
            return


#: words that make "X should be in Y" a guess about where X is, not a wish
_WHEREABOUTS = _W.set("whereabouts")


def whereabouts(clause: Clause, parsed: ParsedClause) -> bool:
    """"The mug should be in a cabinet somewhere", "the remote must be on the sofa
    somewhere": a verbless placement with a word of guessing says where something is."""
    return any(i.text in _WHEREABOUTS for i in clause.items) and bool(parsed.frames) and all(
        f.act is lexicon.Act.PLACE and not f.verb for f in parsed.frames)


def again_sequence(clause: Clause, parsed: ParsedClause) -> None:
    """"turn the tap on and off again": with "again" after it, "on and off" is a sequence
    that ends in the second state, not both at once."""
    words = [i.text for i in clause.items if i.punct is None]
    if not words or words[-1] != "again":
        return
    for f in parsed.frames:
        last: dict[int, Target] = {}
        for t in f.targets:
            last[id(t.head)] = t
        if len(last) < len(f.targets):
            f.targets = [t for t in f.targets if last[id(t.head)] is t]
            f.state = f.targets[-1].state or f.state
            if f.state is not None and f.state[0] is lexicon.Stat.SWITCH:
                f.act = lexicon.Act.SWITCH_ON if f.state[1] else lexicon.Act.SWITCH_OFF


def pointing_question(clause: Clause, parsed: ParsedClause) -> bool:
    """Is the clause a question pointing at an object and where it is?"""
    words = [i.text for i in clause.items if i.punct is None]
    while words and words[0] in ("do", "did", "can", "you", "could"):
        words = words[1:]
    return bool(clause.extra.get("question")) and bool(words) and words[0] in _POINTING and \
        bool(parsed.frames) and all(f.act is lexicon.Act.PLACE for f in parsed.frames)


#: "don't worry about ...", "no rush": reassurance, nothing to do
_NO_WORRIES = _W.set("no_worries")


def small_talk(clause: Clause) -> bool:
    """"Cheers love", "love you!", "you're a star": no object, no state, no pronoun to
    act on, and only verbs that ask for nothing by themselves; or one or two words with
    none of these ("Hiya!", "Careful,")."""
    items = clause.items
    texts = [i.text for i in items]
    if any(i.neg for i in items) and set(texts) & _NO_WORRIES and not any(
            i.state is not None or (i.verb is not None and i.text not in _NO_WORRIES and i.text != "do")
            for i in items):
        return True     # "don't worry about the pan", "no rush"
    if any(i.neg for i in items) and "bother" in texts and any(
            i.verb is not None and i.verb.form == "ing" for i in items[texts.index("bother") + 1:]):
        return True     # "don't bother rinsing it": the act is called off
    words = [i for i in items if i.punct is None and i.text not in ("still", "really", "just", "also")]
    if _SHE_NEEDS_IT.at(words):
        return True     # "don't pack the laptop, she still needs it": why, no request
    if any(i.noun is not None or i.state is not None or i.pron is not None or i.liquid is not None
           or i.recipe is not None for i in items):
        return False
    if clause.extra.get("colon") and any(i.number is not None for i in items):
        return True     # "Right, three jobs:": a heading for the list that follows
    verbs = [i.verb for i in items if i.verb is not None]
    words = [i for i in items if i.punct is None]
    if not verbs and 0 < len(words) <= 2 and clause.link == AND \
            and all(i.number is None and i.robot is None and i.seq is None for i in words):
        return True     # "Hiya!", "Oi,", "Careful,": an interjection, nothing to act on
    return bool(verbs) and all(v.sense.act in _NO_REQUEST for v in verbs)


def requests(p: ParsedClause) -> bool:
    return any(f.act not in _NO_REQUEST and not f.report and not f.wish for f in p.frames)


def condition_groups(clauses: list[Clause]) -> list[list[int]]:
    """The clauses of each "if": the "if" clause and the clauses it coordinates ("if the
    laptop were shut and the pillow were on the armchair")."""
    groups: list[list[int]] = []
    for k, c in enumerate(clauses):
        if c.link == "if":
            groups.append([k])
        elif groups and groups[-1][-1] == k - 1 and c.link == AND and c.sentence == clauses[k - 1].sentence \
                and not (c.items and c.items[0].verb is not None) \
                and not _REQUEST_AFTER_IF.at(c.items):
            # ("if the lamp's still on, could you switch it off": the request the "if" is for)
            groups[-1].append(k)
    return groups


#: states an act makes: "put the lettuce in the fridge once it's been chopped" asks for
#: the chopping too (unlike "once it's in", "once it's on there": where it will be)
_MADE_STATES = frozenset({lexicon.Stat.SLICED, lexicon.Stat.COOKED, lexicon.Stat.TOASTED, lexicon.Stat.CLEAN,
                          lexicon.Stat.HOT, lexicon.Stat.COLD, lexicon.Stat.FILLED})


def own_future(clause: Clause) -> bool:
    """Does the clause say what the speaker will do ("I'll do the rest myself"), not what
    they will want ("I'll need the apple in the fridge")?"""
    return _OWN_FUTURE.at([i for i in clause.items if i.punct is None])


_WISH_WORDS = _W.set("wish_words")


def _wish_for_it(clause: Clause) -> bool:
    """"I'd love it", "it would be great", "I'd appreciate it": the "if" after it says what."""
    words = [i.text for i in clause.items if i.punct is None]
    return bool(words) and (words[-1] == "it" or words[0] == "it") and any(w in _WISH_WORDS for w in words)


def _reported(items: list[Item]) -> bool:
    """"(before) it goes off", "(once) they come out": a pronoun and a verb in the third
    person, what will happen, not something asked."""
    words = [i for i in items if i.punct is None]
    return _REPORTED.at(words)


def drop_conditions(clauses: list[Clause], parsed: list[ParsedClause]) -> set[int]:
    """"If the fridge is open, close it": a state under "if" is the condition of an act
    of its sentence, not a goal (its objects stay for the pronouns). Without such an act
    the "if" clauses are what is wished ("I'd appreciate it if the laptop were closed").
    "When I get home": the speaker's own doings under a subordinator are a time. Returns
    the clauses that were read this way (no note for them)."""
    silent: set[int] = set()
    for k, (c, p) in enumerate(zip(clauses, parsed, strict=True)):
        if own_future(c):
            # "I'll do the rest myself", "I'll be back at seven": the speaker's doing
            parsed[k] = replace(p, frames=[])
            silent.add(k)
            continue
        if c.link in ("after", "before", "while") and p.frames and (is_statement(c.items) or _reported(c.items)) \
                and all((not f.verb or _reported(c.items)) and f.targets
                        and all(t.head.pron is not None for t in f.targets)
                        and (f.state is None or f.state[0] not in _MADE_STATES)
                        and not any(d.noun is not None for t in f.targets for d in t.dest)
                        for f in p.frames):
            # "close the box when it's in", "once it's on there": where something already
            # mentioned will be when the act happens, not a request of its own ("when it's
            # on a burner, put the potato in it" names a place no act asks for: a step)
            parsed[k] = replace(p, frames=[])
            silent.add(k)
            continue
        if c.link not in (AND, THEN, "purpose") and c.items and c.items[0].text in _PERSON \
                and all(f.act in _NO_REQUEST and f.state is None for f in p.frames) \
                and not any(h.noun is not None and h.noun.concept.kind not in ("room", "anything")
                            for h in p.mentions):
            parsed[k] = replace(p, frames=[])
            silent.add(k)
    for group in condition_groups(clauses):
        if any(requests(parsed[k]) for k in group):
            continue
        sentence = clauses[group[0]].sentence
        acted = any(clauses[j].sentence == sentence and j not in group and requests(parsed[j])
                    for j in range(len(clauses)))
        before = clauses[group[0] - 1] if group[0] > 0 else None
        if before is not None and before.sentence == sentence and _wish_for_it(before):
            acted = False   # "I'd love it if X, ... and Y": the "if" is the wish, whatever else is asked
        for k in group:
            if acted:
                parsed[k] = replace(parsed[k], frames=[])
            elif any(f.report for f in parsed[k].frames):
                # "... and the pillow were on the armchair": wished, as the "if" is
                parsed[k] = parse_clause(clauses[k], directive=True)
        if not acted:
            for j, c in enumerate(clauses):
                # "I'd love it if ...": the "it" is what the "if" says, nothing of its own
                if c.sentence == sentence and j not in group and parsed[j].frames and all(
                        f.act in _NO_REQUEST and all(t.head.pron is not None for t in f.targets)
                        and (f.targets or f.means is None)     # "(and then) end up in the bowl"
                        for f in parsed[j].frames):
                    parsed[j] = replace(parsed[j], frames=[], mentions=[])
                    silent.add(j)
    return silent


def _movable(head: Head) -> bool:
    """Can everything the phrase names be picked up (an apple, a mug)?"""
    return phrases.names_only(head, ("pickupable",))


def _fixed_place(head: Head) -> bool:
    """Is the phrase a receptacle that cannot be picked up (a fridge, a sink, a counter)?"""
    return phrases.names_only(head, ("receptacle",), ("pickupable",))


#: prepositions that say where something goes, most telling first
_GOES_TO = _W.seq("goes_to")


def _label_to_place(label: list[Head], nxt: Clause) -> Frame | None:
    """The label's objects put where the item after the colon says, when the item is only
    places ("into the cardboard box on the floor", "off the floor and onto the holder")."""
    items = [i for i in nxt.items if i.punct is None]
    if not items or items[0].prep is None or not all(_movable(h) for h in label):
        return None
    for prep in _GOES_TO:
        at = next((k for k, i in enumerate(items) if i.prep == prep and k + 1 < len(items)
                   and np_start(items[k + 1])), None)
        if at is None:
            continue
        dest, _ = parse_np(items, at + 1)
        if dest is None or dest.noun is None:
            return None
        dest.role = "dest"
        return Frame(lexicon.Act.PLACE, "put", [Target(h, [dest], "in") for h in label], text=nxt.text)
    return None


def _relabelled_placement(c: Clause, nxt: Clause, label: ParsedClause, item: ParsedClause) -> Frame | None:
    """A label that reads as things with their place ("the cloths on the floor"), and after
    the colon only another place ("laundry basket"): the label's place is where the things
    are, the item is where they go."""
    if not c.extra.get("colon") or item.frames or nxt.sentence != c.sentence + 1 or not label.frames:
        return None
    heads = known_objects([i for i in nxt.items if i.noun is not None or i.text not in lexicon.FILLER_WORDS]) or []
    if len(heads) != 1 or heads[0].noun is None or not _fixed_place(heads[0]):
        return None
    if not all(f.act is lexicon.Act.PLACE and f.targets and all(t.dest and _movable(t.head) for t in f.targets)
               for f in label.frames):
        return None
    place = heads[0]
    place.role = "dest"
    return Frame(lexicon.Act.PLACE, "put", [Target(t.head, [place], "in") for f in label.frames for t in f.targets],
                 text=nxt.text)


def labelled_lists(clauses: list[Clause], parsed: list[ParsedClause]) -> set[int]:
    """"Bed: pillow and teddy. Desk: book and laptop.", "Things for the box: the pen and
    the pencil.": a place before a colon, then only objects, puts them there. Returns the
    label clauses (read, no note)."""
    labels: set[int] = set()
    for k in range(len(clauses) - 1):
        c, nxt = clauses[k], clauses[k + 1]
        relabelled = _relabelled_placement(c, nxt, parsed[k], parsed[k + 1])
        if relabelled is not None:
            # "the cloths on the floor: laundry basket": where they are, then where they go
            parsed[k].frames, parsed[k + 1].frames = [], [relabelled]
            labels.add(k)
            continue
        # "things for the desk" reads as a placement that lacks its place
        placing = all(f.act is lexicon.Act.PLACE and not any(t.dest for t in f.targets)
                      for f in parsed[k].frames)
        if not c.extra.get("colon") or not placing or parsed[k + 1].frames \
                or nxt.sentence != c.sentence + 1:
            continue
        named = [h for h in parsed[k].mentions if h.noun is not None]
        listed = known_objects(c.items) or []
        label = listed if len(listed) > len(named) else named or listed    # "keys and watch": both
        if not label:
            continue
        place = label[-1]
        heads = known_objects(nxt.items)
        placed = _label_to_place(label, nxt)
        if placed is not None:
            # "Keys and watch: into the box.", "Cloth: out of the tub, onto the counter."
            parsed[k].frames, parsed[k + 1].frames = [], [placed]
            parsed[k + 1].mentions.extend(t.dest[0] for t in placed.targets[:1])
            labels.add(k)
            continue
        stated = elided_state(nxt, ParsedClause(nxt, [Frame(None, "", [Target(place)])], [place], [])) \
            if place.noun is not None and not heads and nxt.sentence == c.sentence + 1 else []
        if stated:
            # "Light: off.": the state of what the label names
            parsed[k].frames, parsed[k + 1].frames = [], stated
            labels.add(k)
            continue
        if place.noun is None or not heads or any(h.noun is None for h in heads):
            continue
        if len(label) == 1 and len(heads) == 1 and _movable(place) and _fixed_place(heads[0]):
            # "Apple: fridge.": the label is what goes, the item is where
            place, heads = heads[0], label
        place.role = "dest"
        parsed[k].frames = []
        parsed[k + 1].frames = [Frame(lexicon.Act.PLACE, "put", [Target(h, [place], "in") for h in heads],
                                      text=nxt.text)]
        labels.add(k)
    return labels


def attach_means(parsed: list[ParsedClause]) -> None:
    """"cook the potato, the microwave is fine", "the stove is fine - fry the egg": a
    clause that only names an appliance gives the means of the act next to it (the one
    before, else the one after)."""
    for k, p in enumerate(parsed):
        if p.means is None:
            continue
        for other in (parsed[k - 1] if k > 0 else None, parsed[k + 1] if k + 1 < len(parsed) else None):
            if other is not None and other.frames:
                for f in other.frames:
                    f.means = f.means or p.means
                break


#: acts whose object may be left out on purpose ("dim", "water" the plants, "go")
_NO_OBJECT_ACTS = frozenset({lexicon.Act.DIM, lexicon.Act.BRIGHTEN, lexicon.Act.WATER,
                             lexicon.Act.GO, lexicon.Act.MAKE, lexicon.Act.VAGUE})


def share_objects(clauses: list[Clause], parsed: list[ParsedClause]) -> None:
    """"open and close the fridge", "wash and dry the mug": a verb without an object,
    coordinated with the next clause of its sentence, shares that clause's objects."""
    for k in range(len(parsed) - 1):
        p, nxt = parsed[k], parsed[k + 1]
        if clauses[k + 1].sentence != clauses[k].sentence or clauses[k + 1].link != "and" \
                or len(p.frames) != 1 or not nxt.frames or not nxt.frames[0].targets:
            continue
        frame = p.frames[0]
        if frame.targets or frame.act is None or frame.act in _NO_OBJECT_ACTS or frame.report:
            continue
        if frame.means is not None and frame.act is lexicon.Act.PLACE:
            continue    # "... take out and put on the toilet, close cabinet": placed, the thing before
        frame.targets = [Target(t.head, [], None) for t in nxt.frames[0].targets]


def elided_participle(clause: Clause, before: ParsedClause | None) -> list[Frame]:
    """"I'd like my mug washed and then filled with water": a clause that is only a
    state participle asks that state of the objects of the clause before it."""
    words = [i for i in clause.items if i.punct is None and i.text not in lexicon.FILLER_WORDS]
    if before is None or not before.frames or not words or words[0].state is None \
            or words[0].verb is None or words[0].verb.form != "ed" or words[0].noun is not None or before.clause.sentence != clause.sentence \
            or any(np_start(i) and i.liquid is None for i in words[1:]):
        return []
    targets = [t for f in before.frames for t in f.targets if t.head.noun is not None or t.head.pron]
    if not targets:
        return []
    liquid = next((i.liquid for i in words if i.liquid is not None), None)
    return [Frame(lexicon.Act.CAUSE, "get", [Target(t.head) for t in targets], state=words[0].state,
                  liquid=liquid, text=clause.text)]


#: words that may stand beside an elided state: "(then) off again", "back off afterwards"
_ELIDED_STATE_EXTRAS = _W.set("elided_state_extras")


def elided_state(clause: Clause, before: ParsedClause | None) -> list[Frame]:
    """"Tap on, then off again", "open the box, then shut again": a clause that is only a
    particle or a state asks it of the objects of the clause before it."""
    words = [i for i in clause.items if i.punct is None and i.text not in _ELIDED_STATE_EXTRAS
             and (i.text not in lexicon.FILLER_WORDS or i.text in ("on", "off"))
             and i.sub is None and i.seq is None]
    if before is None or not before.frames or len(words) != 1 or words[0].noun is not None \
            or before.clause.sentence != clause.sentence:
        return []
    word = words[0]
    targets = [Target(t.head) for f in before.frames for t in f.targets if t.head.noun is not None or t.head.pron]
    if not targets:
        return []
    if word.text in ("on", "off"):
        on = word.text == "on"
        return [Frame(lexicon.Act.SWITCH_ON if on else lexicon.Act.SWITCH_OFF, "turn", targets,
                      state=(lexicon.Stat.SWITCH, on), particle=word.text, text=clause.text)]
    if word.state is not None and word.prep is None:
        return [Frame(lexicon.Act.CAUSE, "get", targets, state=word.state, text=clause.text)]
    return []


def elided_place(clause: Clause, before: ParsedClause | None) -> list[Frame]:
    """"fill it with water at the sink, then onto a burner": a clause that is only a place
    puts the objects of the clause before it there."""
    items = [i for i in clause.items
             if (i.punct is None and i.seq is None and i.text not in lexicon.FILLER_WORDS) or i.prep is not None]
    if before is None or not before.frames or len(items) < 2 or items[0].prep not in ("onto", "into", "on", "in", "to") \
            or not np_start(items[1]):
        return []
    dest, end = parse_np(items, 1)
    if dest is None or dest.noun is None or end != len(items):
        return []
    targets = [t for f in before.frames for t in f.targets if t.head.noun is not None or t.head.pron]
    if not targets:
        return []
    dest.role = "dest"
    return [Frame(lexicon.Act.PLACE, "put", [Target(t.head, [dest], "in") for t in targets[-1:]], text=clause.text)]


def gapped_objects(clauses: list[Clause], parsed: list[ParsedClause]) -> None:
    """"Put the apple in the fridge, then the tomato" (". Then the tomato."): a clause that
    is only objects, sequenced right after an act, has that act (gapping)."""
    for k in range(1, len(parsed)):
        p, c = parsed[k], clauses[k]
        if p.frames or p.also or (c.link != THEN and "only" not in c.extra) or not parsed[k - 1].frames:
            continue
        heads = known_objects(p.clause.items)
        if heads and all(h.noun is not None for h in heads):
            p.also = heads


def repeat_for_also(parsed: list[ParsedClause]) -> None:
    """"Put the apple in the fridge. Oh, and the tomato too.": the act of the clause
    before, with its place, on the new objects."""
    for k, p in enumerate(parsed):
        words = [i.text for i in p.clause.items if i.punct is None]
        trailing_too = bool(words) and (words[-1] in ("too", "also") or words[-2:] == ["as", "well"])
        before_frames = next((q.frames for q in reversed(parsed[:k]) if q.frames), [])
        located = any(t.head.location for f in before_frames for t in f.targets)
        if trailing_too and located and p.frames and all(f.act is lexicon.Act.PLACE and not f.verb for f in p.frames):
            # "the soap on the bath goes in the sink, and the spray bottle on the toilet too":
            # said like the subject before, where it is, and the act before ("put the book
            # on the shelf and the vase on the table too" keeps its own place)
            heads = []
            for f in p.frames:
                for t in f.targets:
                    t.head.location += [(t.prep or "on", d) for d in t.dest]
                    heads.append(t.head)
            parsed[k] = p = replace(p, frames=[], also=heads)
        if not p.also or p.frames or k == 0:
            continue
        before = next((q for q in reversed(parsed[:k]) if q.frames), None)
        if before is None:
            continue
        last = before.frames[-1]
        model = last.targets[-1] if last.targets else Target(Head())
        # "don't turn off the desk lamp, only the floor lamp": the act itself, not negated
        negated = last.negated and "only" not in p.clause.extra
        p.frames = [replace(last, targets=[Target(h, list(model.dest), model.prep) for h in p.also],
                            instruments=list(last.instruments), room_states=[], negated=negated)]


def fix_up_complaints(parsed: list[ParsedClause]) -> set[int]:
    """"Fridge door wide open, coffee machine still running, light on. Sort it out?": the
    verbless states listed before a request to sort "it" out are complaints (the opposite
    state is asked); the request itself adds nothing. Returns the request clauses."""
    fixing: set[int] = set()
    for k, p in enumerate(parsed):
        if not any(f.act is lexicon.Act.VAGUE and f.targets and all(t.head.pron is not None for t in f.targets)
                   for f in p.frames):
            continue
        described = [f for q in parsed[:k] for f in q.frames
                     if f.state is not None and (f.report or (f.act is None and not f.verb and not f.wish))]
        if not described:
            continue
        for f in described:
            f.report = True       # "the fridge is wide open" already is one
        parsed[k] = replace(p, frames=[f for f in p.frames if f.act is not lexicon.Act.VAGUE])
        fixing.add(k)
    return fixing


def reasons(clauses: list[Clause], parsed: list[ParsedClause]) -> set[int]:
    """"The drawers are all shut, so one of you will have to open one": a report followed
    by "so" and what to do about it is the reason for the request, not a complaint of its
    own (the objects stay for pronouns). Returns the report clauses (no note)."""
    silent: set[int] = set()
    for k in range(len(clauses) - 1):
        p, nxt = parsed[k], clauses[k + 1]
        if p.frames and all(f.report for f in p.frames) and nxt.link == "purpose" \
                and nxt.sentence == clauses[k].sentence and any(i.verb is not None for i in nxt.items):
            parsed[k] = replace(p, frames=[])
            silent.add(k)
    return silent


def told_ahead(items: list[Item], clauses: list[Clause], parsed: list[ParsedClause]) -> set[int]:
    """"By the time I'm back the keys are in the box", "tomorrow morning the laptop will be
    shut": under a narrative cue (``rule_words.json``, ``stated``) a statement of where a
    thing is or what state it is in tells the end state, so it is read as wished, as after
    "make sure", from the cue on; an act nobody did asks nothing. Other past and perfect
    tenses ("has been on all night"), negations and questions stay as they were. Returns
    the clauses of acts nobody did (no note for them)."""
    silent: set[int] = set()
    cues = find(items, 0, len(items), load_rule_words().stated.narrative_cues)
    if not cues:
        return silent
    first = items[cues[0][0]]
    # the clause holding the cue, or, when its first word became the link ("when I walk
    # in, ..."), the first one holding a word after it
    after = {id(i) for i in items[cues[0][0]:]}
    cued = next((k for k, c in enumerate(clauses) if any(id(i) in after for i in c.items)), None)
    if cued is None:
        return silent
    if clauses[cued].items[0] is not first:
        cued += 1   # "... in a cabinet where nobody can find it": the cue frames what follows it
    for k, (c, p) in enumerate(zip(clauses, parsed, strict=True)):
        if k >= cued and p.frames and all(f.report and f.past and f.negated for f in p.frames):
            # "... and nobody switched the light off": in the picture the act did not happen,
            # so it asks nothing (what it names stays for the rest of the reading)
            parsed[k] = replace(p, frames=[])
            silent.add(k)
            continue
        if k < cued or not p.frames or c.extra.get("question") or c.link not in (AND, THEN) \
                or any(i.text == "been" for i in c.items):
            continue
        if not all(f.report and not f.past and not f.negated and f.targets
                   and all(t.head.pron is None for t in f.targets) for f in p.frames):
            continue
        again = parse_clause(c, directive=True)
        if again.frames and not any(f.report or f.negated for f in again.frames):
            parsed[k] = again
    return silent
