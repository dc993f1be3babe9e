"""Which object types a prompt lists in detail: what the instruction names, what it
implies, and what a goal on those needs.

The LLM prompts list these types in full (ids, abilities, place, state) and only name the
others: a scene has 30-90 object types and an instruction touches a handful, so listing
everything made the PFG prompt 3,500-5,500 tokens, most of it noise for a small model.
But a listing that hides what the instruction *implies* forces a strong model to guess,
so the listing follows the instruction's intent (:func:`focus_types`):

- the types its nouns name (the offline parser's tagger: lexicon, synonyms, its spelling
  index for typos and split words) and close sound-alikes of the scene's type names;
- the types a draft reading names (the offline parser's, when there is one);
- everything in or on a receptacle or place the instruction names ("everything in the
  fridge except ...", "clear the counter");
- every object whose state an intent touches: all light sources, blinds and screens for
  light or darkness, all openables for "close everything", screens and appliances for
  quiet, all switchables for "turn everything off";
- closed over what a goal on them needs (slices and their source, a burner's knob, what
  holds the objects now);
- the whole scene when it is small.

The same sets tell the answer checks (:mod:`emboteam.pfg.answer_checks`) what the
instruction names or implies: a condition about a type the listing shows is never
"copied from the worked example".
"""

from __future__ import annotations

import difflib
import itertools
import re
from collections.abc import Iterable

from emboteam.errors import EmboTeamError
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.catalogue import SAME_PLACE, load_catalogue
from emboteam.world.goals import Condition, ObjectRef
from emboteam.world.state import WorldState

#: a scene with at most this many objects is listed whole (it costs less than a guess)
SMALL_SCENE_OBJECTS = 30

#: types whose state makes a room lit or dark, and what glows
LIGHT_TYPES = frozenset({"LightSwitch", "DeskLamp", "FloorLamp", "Candle", "Blinds", "Television", "Laptop",
                         "Desktop", "CellPhone"})
#: what makes noise in a home
NOISE_TYPES = frozenset({"Television", "Laptop", "Desktop", "CellPhone", "AlarmClock", "Faucet", "ShowerHead",
                         "Microwave", "CoffeeMachine", "Toaster"})

_WORD = re.compile(r"[a-z]+")
#: words of an intent about light or darkness
_LIGHT_WORDS = frozenset({"candlelight", "candlelit", "romantic", "moody", "cosy", "cozy",
                          "light", "lights", "lit", "lamp", "lamps", "dark", "darker", "darkness", "bright",
                          "brighter", "brightness", "dim", "dimmer", "glare", "sun", "sunlight", "sunshine",
                          "blind", "blinds", "shade", "shades", "curtain", "curtains", "glow", "glowing", "pitch",
                          "candle", "candles", "illuminate", "illuminated", "see", "reading", "screen", "screens"})
#: words of an intent about noise
_QUIET_WORDS = frozenset({"quiet", "quieter", "noise", "noisy", "loud", "louder", "silence", "silent", "racket",
                          "din", "hum", "humming", "buzz", "buzzing", "sound", "volume", "peace", "peaceful",
                          "sleep", "sleeping", "asleep", "nap", "napping", "blaring", "beeping", "ringing"})
#: words that make an act apply to everything of its kind
_ALL_WORDS = frozenset({"everything", "all", "anything", "every", "each", "nothing", "whatever", "stuff"})
_CLOSE_WORDS = frozenset({"close", "closed", "shut", "open", "opened", "ajar", "draft", "draught", "drafty",
                          "draughty", "gaping"})
_SWITCH_WORDS = frozenset({"off", "on", "power", "powered", "electricity", "energy", "unplug", "plugged",
                           "running", "switch", "switched", "turn", "turned"})
#: words of a chore too loose to narrow: the whole scene is listed
_WHOLE_SCENE_WORDS = frozenset({"tidy", "tidied", "mess", "messy", "clutter", "cluttered", "declutter",
                                "untidy", "straighten", "sort"})
#: the devices a result implies: a word of the result -> the types that produce it (coffee
#: comes from the coffee machine, cold from the fridge, heat from an oven or a burner)
IMPLIED_DEVICES: tuple[tuple[frozenset[str], frozenset[str]], ...] = (
    (frozenset({"coffee", "espresso", "latte", "cappuccino", "brew"}), frozenset({"CoffeeMachine", "Mug"})),
    (frozenset({"cold", "colder", "chill", "chilled", "chilling", "cool", "cooled", "cooler", "warm", "fresh",
                "soft", "wilting", "wilted", "spoil", "spoiling", "rot", "rotting", "refrigerate", "frozen"}),
     frozenset({"Fridge"})),
    (frozenset({"hot", "heat", "heated", "warm", "warmed", "cook", "cooked", "bake", "baked", "fry", "fried",
                "boil", "boiled", "toast", "toasted", "nuke", "nuker", "zap", "roast", "roasted"}),
     frozenset({"Microwave", "StoveBurner", "StoveKnob", "Toaster", "Pan", "Pot"})),
    (frozenset({"wash", "washed", "rinse", "rinsed", "clean", "cleaned", "dirty", "filthy", "scrub", "water",
                "tap"}), frozenset({"SinkBasin", "Faucet"})),
    (frozenset({"match", "game", "show", "news", "channel", "watch", "film", "movie", "telly", "programme",
                "program"}), frozenset({"Television", "RemoteControl"})),
    (frozenset({"read", "reading", "book"}), frozenset({"DeskLamp", "FloorLamp", "LightSwitch"})),
)


def instruction_types(instruction: str) -> set[str]:
    """Catalogue types the instruction's nouns can name (synonyms, fallbacks and the
    offline tagger's spelling corrections included)."""
    from emboteam.pfg.offline.tagger import tag

    try:
        items = tag(instruction)
    except EmboTeamError:  # a tagger that refuses the text names no type
        return set()
    found: set[str] = set()
    for item in items:
        if item.noun is not None:
            found.update(item.noun.concept.types)
            found.update(item.noun.concept.fallback)
    return found


#: spellings that sound alike, folded before comparing ("sync" / "sink", "hold her" / "holder")
_SOUND_FOLDS = (("ph", "f"), ("ck", "k"), ("dh", "d"), ("y", "i"), ("c", "k"), ("z", "s"))
_DOUBLE = re.compile(r"(.)\1+")
_VOWELS = re.compile(r"[aeiou]")
_CAMEL = re.compile(r"[A-Z][a-z]*")


def sounds(text: str) -> str:
    """A rough sound key: alike-sounding spellings folded, doubled letters single
    (``tomotto`` and ``tomato`` -> ``tomoto``/``tomato``; ``sync`` -> ``sink``)."""
    for a, b in _SOUND_FOLDS:
        text = text.replace(a, b)
    return _DOUBLE.sub(r"\1", text)


def word_grams(instruction: str) -> set[str]:
    """Words, two and three adjacent words run together (split words: "to motto", "micro
    wave"), and "X of the Y" read as "YX" (a non-native "curtain of the shower")."""
    words = _WORD.findall(instruction.lower())
    grams = set(words) | {a + b for a, b in itertools.pairwise(words)}
    grams |= {a + b + c for a, b, c in zip(words, words[1:], words[2:], strict=False)}
    for i in range(len(words) - 3):
        if words[i + 1] == "of" and words[i + 2] in ("the", "a", "an", "my"):
            grams.add(words[i + 3] + words[i])
    for i in range(len(words) - 2):
        if words[i + 1] == "of":
            grams.add(words[i + 2] + words[i])
    return grams


def sound_alike_types(instruction: str, present: Iterable[str]) -> set[str]:
    """Scene types whose name the instruction's words sound or look like (a transcript's
    "tomatoe", "sync", "to motto", a text's "brd", "curtain of the shower"): a close match
    of sound keys (``difflib``, standard library; names of 4 letters and more) or the same
    consonants (3 or more: "brd" is bread). The offline tagger's spelling index covers the
    lexicon's words; this covers the scene's own type names, which an instruction may
    garble differently."""
    grams = word_grams(instruction)
    keys = {sounds(g) for g in grams if len(g) >= 4}
    skeletons = {_VOWELS.sub("", g) for g in grams if len(g) >= 3}
    skeletons = {s for s in skeletons if len(s) >= 3}
    words = set(_WORD.findall(instruction.lower()))
    found: set[str] = set()
    for t in present:
        name = t.lower()
        head = _CAMEL.findall(t)[-1].lower() if _CAMEL.findall(t) else name
        if len(head) >= 4 and (head in words or head + "s" in words):  # "the curtain": ShowerCurtain
            found.add(t)
            continue
        if len(name) < 4:
            continue
        key = sounds(name)
        if _VOWELS.sub("", name) in skeletons:
            found.add(t)
            continue
        for g in keys:
            if abs(len(g) - len(key)) <= 2 and g[0] == key[0] and difflib.SequenceMatcher(None, g, key).ratio() >= 0.8:
                found.add(t)
                break
    return found


def run_together_types(instruction: str) -> set[str]:
    """Types the lexicon finds in split or sound-alike words run together ("hold her":
    holder, a towel or paper holder), through the offline tagger."""
    words = _WORD.findall(instruction.lower())
    joined = [sounds(a + b) for a, b in itertools.pairwise(words)]
    return instruction_types(" ".join(joined)) if joined else set()


def intent_types(instruction: str, state: WorldState) -> set[str]:
    """Types whose state the instruction's intent touches without naming them: light and
    darkness, noise, closing or switching everything."""
    words = set(_WORD.findall(instruction.lower()))
    live = [o for o in state.objects.values() if not o.gone]
    out: set[str] = set()
    for cue, types in IMPLIED_DEVICES:
        if words & cue:
            out |= {o.type for o in live if o.type in types}
    if words & _LIGHT_WORDS:
        out |= {o.type for o in live if o.type in LIGHT_TYPES}
    if words & _QUIET_WORDS:
        out |= {o.type for o in live if o.type in NOISE_TYPES}
    if words & _ALL_WORDS and words & _CLOSE_WORDS:
        out |= {o.type for o in live if o.has("openable")}
    if words & _ALL_WORDS and words & _SWITCH_WORDS:
        out |= {o.type for o in live if o.has("toggleable")}
    return out


def contents_types(places: Iterable[str], state: WorldState) -> set[str]:
    """Types of what is in or on an object of the ``places`` types (the sink's basin and
    the bathtub's count as the same place), nested contents included."""
    wanted = {alias for p in places for alias in SAME_PLACE.get(p, frozenset({p}))}
    live = {o.id: o for o in state.objects.values() if not o.gone}
    holders = {oid for oid, o in live.items() if o.type in wanted}
    out: set[str] = set()
    for o in live.values():
        parent, hops = o.parent, 0
        while parent is not None and parent in live and hops < 4:
            if parent in holders:
                out.add(o.type)
                break
            parent, hops = live[parent].parent, hops + 1
    return out


def ref_types(ref: ObjectRef, state: WorldState) -> set[str]:
    """The types an object reference names (an id's type, or its types)."""
    if ref.id is not None:
        obj = state.objects.get(ref.id)
        return {obj.type} if obj is not None else set()
    return set(ref.types)


def condition_types(cond: Condition, state: WorldState) -> set[str]:
    types = ref_types(cond.subject, state)
    if cond.receptacle is not None:
        types |= ref_types(cond.receptacle, state)
    return types


def spec_types(spec: TaskSpec, state: WorldState) -> set[str]:
    return {t for s in spec.subtasks for c in s.goal for t in condition_types(c, state)}


def related_types(types: Iterable[str], state: WorldState, *, holders: bool = True) -> set[str]:
    """``types`` closed under what a goal on them needs to know about: slices and what
    they are cut from, the knob that switches a burner (and back), and (``holders``) what
    holds the objects now in detail (each object's own line already says where it is)."""
    cat = load_catalogue()
    out = set(types)
    for t in list(out):
        if (product := cat.slice_product(t)) is not None:
            out.add(product[0])
        if (source := cat.source_type(t)) is not None:
            out.add(source)
    live = [o for o in state.objects.values() if not o.gone]
    by_id = {o.id: o for o in live}
    for o in live:
        controlled = {by_id[c].type for c in o.controls if c in by_id}
        if o.type in out:
            out |= controlled
        elif controlled & out:
            out.add(o.type)
    if holders:
        for o in live:
            if o.type in out and o.parent in by_id:
                out.add(by_id[o.parent].type)
    return out


def named_types(instruction: str, state: WorldState, draft: TaskSpec | None = None) -> set[str]:
    """The scene's types the instruction names or implies (before closing over relations):
    its nouns, sound-alikes, a draft's types, what its named places hold, its intents."""
    cat = load_catalogue()
    present = {o.type for o in state.objects.values() if not o.gone}
    products = {p[0] for t in present if (p := cat.slice_product(t)) is not None}
    named = (instruction_types(instruction) | sound_alike_types(instruction, present)
             | run_together_types(instruction)) & (present | products)
    touched = set(named)
    if draft is not None:
        touched |= spec_types(draft, state) & (present | products)
    touched |= contents_types(named, state)
    touched |= intent_types(instruction, state)
    return touched


def focus_types(instruction: str, state: WorldState, draft: TaskSpec | None = None) -> set[str] | None:
    """The types a prompt lists in full, or None (list everything): when the scene is
    small, or when the instruction names and implies no type present in the scene (a
    chore like "get breakfast ready": the model needs the whole scene to choose from)."""
    live = [o for o in state.objects.values() if not o.gone]
    if len(live) <= SMALL_SCENE_OBJECTS:
        return None
    if set(_WORD.findall(instruction.lower())) & _WHOLE_SCENE_WORDS:
        return None
    touched = named_types(instruction, state, draft)
    if not touched:
        return None
    present = {o.type for o in live}
    return related_types(touched, state, holders=False) & present
