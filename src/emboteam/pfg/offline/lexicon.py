"""The offline parser's lexicon: words and phrases and what they mean to a household
robot team. Pure data, read by the tagger, the grounder and the semantics.

How to extend (docs/offline_parser.md has the long form):

- a new name for an object: add ``"phrase": _obj("Type")`` to :data:`NOUNS` (singular;
  plurals are derived); for a name that means several types, list them in order of
  preference and give fallbacks for scenes that lack them;
- a new category: add it to :data:`NOUNS` with ``kind="category"``;
- a new verb: add its lemma to :data:`VERBS` with its :class:`Act`; irregular forms go
  to :data:`IRREGULAR_VERBS`; a verb whose meaning changes with a particle ("throw away")
  goes to :data:`PARTICLE_VERBS`;
- a new state word ("spotless"): add it to :data:`STATES`.

Every AI2-THOR type is also reachable by its own name, split (``coffee table``) or run
together (``coffeetable``): :func:`nouns` adds those entries from the catalogue.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import Enum
from functools import cache

from emboteam.pfg.offline.text import split_camel
from emboteam.world.catalogue import load_catalogue


class Act(str, Enum):
    """What a verb asks for; the semantics turns each into goal conditions."""

    PLACE = "place"          # put X in/on Y
    TRASH = "trash"          # X into a garbage can
    HOLD = "hold"            # pick X up
    SLICE = "slice"
    BREAK = "break"
    OPEN = "open"
    CLOSE = "close"
    SWITCH = "switch"        # needs a particle: turn on / switch off
    SWITCH_ON = "switch_on"
    SWITCH_OFF = "switch_off"
    TOGGLE = "toggle"        # flip whatever the state is
    HEAT = "heat"
    MICROWAVE = "microwave"  # heat, and the microwave is the means
    COOK = "cook"
    TOAST = "toast"          # slice bread and cook the slices
    COOL = "cool"
    CLEAN = "clean"
    DIRTY = "dirty"
    FILL = "fill"
    POUR = "pour"            # pour LIQUID into X
    WATER = "water"          # water the plant
    MAKE = "make"            # make coffee / make the room dark
    WATCH = "watch"          # watch tv: the tv is on
    GO = "go"                # intransitive motion: X goes/belongs in Y
    CAUSE = "cause"          # leave/keep/get/have X STATE
    EMPTY = "empty"
    VAGUE = "vague"          # tidy, organise: no clear household reading
    DIM = "dim"              # dim/darken: lights off
    BRIGHTEN = "brighten"


class Stat(str, Enum):
    """A state a word can name; with a polarity it becomes one goal predicate."""

    SWITCH = "switch"
    OPEN = "open"
    HOT = "hot"
    COLD = "cold"
    COOKED = "cooked"
    CLEAN = "clean"
    SLICED = "sliced"
    BROKEN = "broken"
    FILLED = "filled"
    HELD = "held"
    BRIGHT = "bright"        # of a room: its lights
    TOASTED = "toasted"


#: states whose negation is another state ("not open" = closed)
INVERTIBLE = frozenset({Stat.SWITCH, Stat.OPEN, Stat.CLEAN, Stat.BRIGHT})


@dataclass(frozen=True, slots=True)
class VerbSense:
    act: Act
    #: a generic verb (get, have, go): a clause with it and an unknown noun is small talk
    #: ("when you get a chance"), not an error
    weak: bool = False


def _v(act: Act, weak: bool = False) -> VerbSense:
    return VerbSense(act, weak)


A = Act
VERBS: dict[str, VerbSense] = {
    # placing
    **{w: _v(A.PLACE) for w in (
        "put", "place", "move", "store", "carry", "transfer", "stick", "pop", "lay", "drop", "bung", "stand",
        "return", "relocate", "position", "deposit", "stack", "load", "insert", "hang",
        "tuck", "shove", "slide", "shift", "stash", "rest", "deliver", "bring", "fetch",
        "take", "throw", "toss", "send", "set", "arrange", "replace", "restock", "transport",
        "haul", "plonk", "plop", "dump", "pack", "stow", "slot", "file", "nestle", "park",
        "stand", "prop", "perch", "pull", "roll", "abandon")},
    # placing where the verb says: "shelve the book" is on a shelf
    "shelve": _v(A.PLACE),
    # putting it in the garbage
    **{w: _v(A.TRASH) for w in (
        "trash", "discard", "dispose", "bin", "junk", "chuck", "ditch", "scrap", "garbage")},
    **{w: _v(A.HOLD) for w in (
        "pick", "grab", "hold", "lift", "collect", "retrieve", "obtain", "snatch", "seize", "pinch", "nick", "fish",
        "hand", "give", "find", "locate", "acquire")},
    **{w: _v(A.SLICE) for w in (
        "slice", "cut", "chop", "dice", "mince", "carve", "cube", "julienne", "halve",
        "quarter", "shred")},
    **{w: _v(A.BREAK) for w in (
        "break", "smash", "shatter", "crack", "destroy", "crush", "wreck", "bust")},
    "open": _v(A.OPEN), "unclose": _v(A.OPEN), "unseal": _v(A.OPEN), "raise": _v(A.OPEN),
    **{w: _v(A.CLOSE) for w in ("close", "shut", "seal", "lower", "draw", "lock")},
    **{w: _v(A.SWITCH) for w in ("turn", "switch", "flip", "flick", "power", "click")},
    **{w: _v(A.SWITCH_ON) for w in (
        "activate", "start", "run", "boot", "enable", "light", "ignite", "kindle",
        "illuminate", "fire")},
    **{w: _v(A.SWITCH_OFF) for w in (
        "deactivate", "stop", "kill", "disable", "extinguish", "douse", "unplug", "blow",
        "snuff")},
    "toggle": _v(A.TOGGLE),
    **{w: _v(A.HEAT) for w in ("heat", "warm", "reheat", "defrost", "thaw")},
    **{w: _v(A.MICROWAVE) for w in ("microwave", "nuke", "zap")},
    **{w: _v(A.COOK) for w in (
        "cook", "fry", "boil", "bake", "roast", "grill", "saute", "steam", "poach",
        "scramble", "sear", "barbecue", "simmer", "braise")},
    "toast": _v(A.TOAST),
    **{w: _v(A.COOL) for w in ("chill", "cool", "refrigerate", "freeze", "ice", "refridgerate")},
    **{w: _v(A.CLEAN) for w in (
        "clean", "wash", "rinse", "scrub", "wipe", "soak", "cleanse", "scour", "sanitize",
        "sanitise", "disinfect")},
    **{w: _v(A.DIRTY) for w in ("dirty", "soil", "stain", "smudge", "muddy")},
    **{w: _v(A.FILL) for w in ("fill", "refill")},
    "pour": _v(A.POUR),
    "water": _v(A.WATER),
    **{w: _v(A.MAKE) for w in ("make", "prepare", "brew", "fix", "whip", "serve")},
    "watch": _v(A.WATCH),
    **{w: _v(A.GO, weak=True) for w in (
        "go", "belong", "end", "stay", "live", "sit", "remain", "lie", "wind", "land", "come")},
    **{w: _v(A.CAUSE, weak=True) for w in (
        "leave", "keep", "get", "have", "render", "want", "need", "like", "prefer", "love",
        "fancy", "crave")},
    "empty": _v(A.EMPTY),
    **{w: _v(A.VAGUE) for w in (
        "tidy", "organize", "organise", "declutter", "straighten", "sort", "neaten")},
    **{w: _v(A.DIM) for w in ("dim", "darken", "blacken")},
    "brighten": _v(A.BRIGHTEN), "lighten": _v(A.BRIGHTEN),
}

#: verbs that name where things go: "shelve the book" is ``inside(Book, Shelf)``
VERB_PLACES: dict[str, tuple[str, ...]] = {"shelve": ("Shelf", "ShelvingUnit")}

#: (verb, particle) -> sense, where the particle changes what the verb means
PARTICLE_VERBS: dict[tuple[str, str], VerbSense] = {
    ("throw", "away"): _v(A.TRASH), ("throw", "out"): _v(A.TRASH),
    ("toss", "away"): _v(A.TRASH), ("toss", "out"): _v(A.TRASH),
    ("chuck", "away"): _v(A.TRASH), ("chuck", "out"): _v(A.TRASH),
    ("dump", "out"): _v(A.TRASH), ("bin", "away"): _v(A.TRASH),
    ("pick", "up"): _v(A.HOLD), ("take", "out"): _v(A.HOLD), ("take", "up"): _v(A.HOLD),
    ("get", "out"): _v(A.HOLD), ("pull", "out"): _v(A.HOLD), ("fish", "out"): _v(A.HOLD),
    ("pull", "back"): _v(A.OPEN), ("draw", "back"): _v(A.OPEN), ("crack", "open"): _v(A.OPEN),
    ("shut", "off"): _v(A.SWITCH_OFF), ("shut", "down"): _v(A.SWITCH_OFF),
    ("power", "up"): _v(A.SWITCH_ON), ("power", "down"): _v(A.SWITCH_OFF),
    ("put", "out"): _v(A.SWITCH_OFF), ("blow", "out"): _v(A.SWITCH_OFF),
    ("light", "up"): _v(A.SWITCH_ON), ("fire", "up"): _v(A.SWITCH_ON),
    ("start", "up"): _v(A.SWITCH_ON), ("boot", "up"): _v(A.SWITCH_ON),
    ("cool", "down"): _v(A.COOL), ("end", "up"): _v(A.GO, weak=True),
    ("clean", "up"): _v(A.CLEAN), ("wash", "up"): _v(A.CLEAN),
    ("mess", "up"): _v(A.DIRTY), ("fill", "up"): _v(A.FILL), ("top", "up"): _v(A.FILL),
    ("whip", "up"): _v(A.MAKE),
    **{(w, p): _v(A.CLEAN) for w in ("rinse", "wash", "wipe", "clean", "scrub")
       for p in ("off", "out", "down")},
}

#: particles that may follow a verb (or its object)
PARTICLES = frozenset({"on", "off", "up", "down", "away", "out", "back", "over", "around",
                       "aside", "in"})

#: irregular inflections -> lemma (regular ones are handled by rules in morphology)
IRREGULAR_VERBS: dict[str, str] = {
    "threw": "throw", "thrown": "throw", "took": "take", "taken": "take",
    "brought": "bring", "kept": "keep", "left": "leave", "held": "hold", "got": "get",
    "gotten": "get", "made": "make", "broke": "break", "broken": "break", "froze": "freeze",
    "frozen": "freeze", "went": "go", "gone": "go", "gave": "give", "given": "give",
    "hung": "hang", "lit": "light", "stuck": "stick", "laid": "lay", "lain": "lie",
    "found": "find", "sat": "sit", "ran": "run", "had": "have", "has": "have",
    "shut": "shut", "cut": "cut", "put": "put", "set": "set", "dumped": "dump",
    "ended": "end", "needs": "need", "wound": "wind", "lying": "lie", "blew": "blow", "blown": "blow",
    "fed": "feed", "swept": "sweep", "chose": "choose", "done": "do", "did": "do",
}

#: state words: adjectives and participles a goal can be stated with
STATES: dict[str, tuple[Stat, bool]] = {
    **{w: (Stat.SWITCH, True) for w in ("on", "running", "active", "powered", "lit", "lighted",
                                        "burning", "started")},
    **{w: (Stat.SWITCH, False) for w in ("off", "inactive", "unplugged", "extinguished")},
    **{w: (Stat.OPEN, True) for w in ("open", "opened", "unlocked", "ajar")},
    **{w: (Stat.OPEN, False) for w in ("closed", "shut", "locked", "sealed")},
    **{w: (Stat.HOT, True) for w in ("hot", "warm", "heated", "warmed", "microwaved",
                                     "reheated", "toasty", "steaming")},
    **{w: (Stat.COLD, True) for w in ("cold", "chilled", "cool", "cooled", "frozen",
                                      "refrigerated", "icy", "chilly")},
    **{w: (Stat.COOKED, True) for w in ("cooked", "fried", "boiled", "baked", "roasted",
                                        "grilled", "sauteed", "steamed", "poached",
                                        "scrambled")},
    "toasted": (Stat.TOASTED, True),
    **{w: (Stat.CLEAN, True) for w in ("clean", "cleaned", "washed", "rinsed", "spotless",
                                       "scrubbed", "wiped", "sanitized")},
    **{w: (Stat.CLEAN, False) for w in ("dirty", "filthy", "unwashed", "soiled", "grimy",
                                        "stained", "greasy")},
    **{w: (Stat.SLICED, True) for w in ("sliced", "chopped", "diced", "minced", "cubed",
                                        "halved", "carved", "shredded")},
    **{w: (Stat.BROKEN, True) for w in ("broken", "smashed", "shattered", "cracked")},
    **{w: (Stat.FILLED, True) for w in ("full", "filled")},
    **{w: (Stat.BRIGHT, False) for w in ("dark", "darker", "dim", "gloomy", "pitch")},
    **{w: (Stat.BRIGHT, True) for w in ("bright", "brighter", "illuminated", "lighter")},
}

#: the state each act brings about (for negation: "don't turn on" = off)
ACT_STATE: dict[Act, tuple[Stat, bool]] = {
    A.SWITCH_ON: (Stat.SWITCH, True), A.SWITCH_OFF: (Stat.SWITCH, False),
    A.OPEN: (Stat.OPEN, True), A.CLOSE: (Stat.OPEN, False), A.CLEAN: (Stat.CLEAN, True),
    A.DIRTY: (Stat.CLEAN, False), A.HEAT: (Stat.HOT, True), A.COOL: (Stat.COLD, True),
    A.COOK: (Stat.COOKED, True), A.SLICE: (Stat.SLICED, True), A.BREAK: (Stat.BROKEN, True),
    A.FILL: (Stat.FILLED, True), A.HOLD: (Stat.HELD, True), A.WATCH: (Stat.SWITCH, True),
    A.DIM: (Stat.BRIGHT, False), A.BRIGHTEN: (Stat.BRIGHT, True),
    A.MICROWAVE: (Stat.HOT, True), A.TOAST: (Stat.TOASTED, True),
}

#: prepositions -> a canonical role
PREPOSITIONS: dict[str, str] = {
    "in": "in", "into": "in", "inside": "in", "within": "in", "in to": "in", "inside of": "in",
    "on": "on", "onto": "on", "upon": "on", "atop": "on", "on top of": "on", "on to": "on",
    "to": "to", "towards": "to", "toward": "to", "at": "at", "over to": "to",
    "from": "from", "out of": "from", "off": "from", "off of": "from",
    "with": "with", "using": "with",
    "of": "of", "for": "for",
    "next to": "near", "beside": "near", "besides": "near", "near": "near", "by": "by",
    "close to": "near", "alongside": "near",
    "under": "under", "underneath": "under", "beneath": "under", "below": "under",
    "behind": "under", "in front of": "near",
}

DETERMINERS = frozenset({"the", "a", "an", "this", "that", "these", "those", "my", "your",
                         "our", "his", "her", "their", "its", "some", "any", "another",
                         "other", "same", "one"})
QUANTIFIERS = frozenset({"all", "every", "each", "both", "everything", "whole", "entire"})
PRONOUNS = frozenset({"it", "them", "they", "itself", "themselves", "this", "that", "these",
                      "those", "one", "ones", "some"})
NEGATIONS = frozenset({"not", "never", "no", "nobody", "nothing", "neither", "nor"})
#: copulas and modals: "the fridge should be closed", "the tv must be off"
COPULAS = frozenset({"is", "are", "be", "was", "were", "been", "being", "am", "should", "must",
                     "shall", "will", "would", "could", "can", "may", "might", "ought",
                     "needs", "need", "has", "have", "had", "to", "got", "gets", "becomes",
                     "become", "stays", "remain", "remains", "going", "do", "does", "did"})
#: modal words that make a statement a wish ("should be closed") rather than a report
#: of how things are ("is open")
MODALS = frozenset({"should", "must", "shall", "will", "would", "could", "can", "ought",
                    "needs", "need", "has", "have", "want", "wants", "like", "prefer",
                    "love", "make", "ensure", "sure", "let", "may", "might", "going"})

NUMBERS: dict[str, int] = {
    "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8,
    "nine": 9, "ten": 10, "eleven": 11, "twelve": 12, "thirteen": 13, "fourteen": 14,
    "fifteen": 15, "sixteen": 16, "twenty": 20, "single": 1, "couple": 2, "pair": 2,
    "both": 2, "few": 3, "several": 3, "dozen": 12, "half": 1,
}
#: counts that are estimates: clamp them to what the scene has
VAGUE_COUNTS = frozenset({"few", "several", "some", "couple"})
ORDINALS: dict[str, int] = {"first": 1, "second": 2, "third": 3, "fourth": 4, "fifth": 5,
                            "sixth": 6, "last": -1}

#: connectives that order what follows after what precedes
SEQUENCE_MARKERS: tuple[str, ...] = (
    "and then", "and after that", "and afterwards", "and finally", "and next", "and later",
    "then", "after that", "after this", "after which", "afterwards", "afterward", "next",
    "finally", "lastly", "later", "subsequently", "thereafter", "once done",
    "once that is done", "once this is done", "once finished", "when done",
    "when that is done", "when finished", "when you are done", "once you are done",
    "after you are done", "after doing that", "after doing so", "and when done",
    "after", "than",  # "than" is the commonest typo of "then" ("..., than close it")
)
#: subordinators: (word, relation); "after X" -> the main clause follows X
SUBORDINATORS: dict[str, str] = {
    "after": "after", "once": "after", "when": "after", "as soon as": "after",
    "whenever": "after", "before": "before", "until": "before", "while": "while",
    "whilst": "while", "as": "while", "by": "by", "so that": "purpose", "so": "purpose",
    "if": "if",
}

#: words that carry no content for the parser: politeness, discourse, hedges. Matched
#: anywhere outside noun phrases and dropped. Also the words spelling correction must
#: never "correct" into object names.
FILLER_WORDS = frozenset(["please", "kindly", "just", "now", "also", "too", "ok", "okay", "alright", "hey", "hi", "hello", "oh", "um", "uh", "hmm", "well", "so", "yes", "yeah", "thanks", "thank", "cheers", "really", "quickly", "carefully", "gently", "immediately", "right", "away", "soon", "asap", "maybe", "perhaps", "possibly", "actually", "basically", "simply", "still", "again", "even", "already", "yet", "then", "there", "here", "you", "someone", "somebody", "anyone", "anybody", "robot", "robots", "team", "everyone", "everybody", "guys", "i", "we", "me", "us", "my", "our", "your", "mine", "yours", "myself", "yourself", "yourselves", "ourselves", "would", "could", "can", "will", "might", "may", "shall", "should", "must", "mind", "possible", "able", "time", "chance", "moment", "be", "a", "dear", "favor", "favour", "great", "nice", "good", "lovely", "wonderful", "awesome", "appreciated", "appreciate", "let", "us", "let", "think", "wonder", "wondering", "guess", "hope", "wish", "suppose", "means", "way", "bit", "thing", "things", "for", "of", "in", "on", "at", "by", "with", "to", "from", "as", "if", "what", "which", "who", "whom", "whose", "how", "why", "where"])

#: ordinary English words that are not in the lexicon but must not be spelling-corrected
#: into one of its words ("there" is one transposition from "three")
COMMON_WORDS = FILLER_WORDS | frozenset(["the", "a", "an", "and", "or", "but", "nor", "not", "no", "is", "are", "was", "were", "am", "been", "being", "be", "do", "does", "did", "done", "doing", "have", "has", "had", "having", "it", "its", "they", "them", "their", "theirs", "this", "that", "these", "those", "there", "here", "where", "when", "while", "whilst", "after", "before", "once", "until", "than", "then", "so", "because", "since", "though", "although", "into", "onto", "upon", "over", "under", "above", "below", "across", "through", "about", "around", "near", "far", "out", "up", "down", "off", "away", "back", "every", "each", "all", "both", "some", "any", "many", "much", "more", "most", "less", "least", "few", "several", "other", "another", "same", "such", "own", "only", "very", "quite", "rather", "pretty", "fairly", "too", "enough", "almost", "big", "small", "large", "little", "tiny", "huge", "long", "short", "tall", "old", "new", "red", "green", "blue", "yellow", "black", "white", "brown", "pink", "purple", "orange", "grey", "gray", "silver", "gold", "wooden", "plastic", "metal", "glass", "left", "right", "top", "bottom", "middle", "front", "side", "near", "nearest", "closest", "first", "second", "third", "last", "next", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "dinner", "lunch", "breakfast", "supper", "meal", "food", "room", "house", "home", "kitchen", "bedroom", "bathroom", "living", "lounge", "office", "area", "place", "spot", "corner", "wall", "door", "doors", "today", "tonight", "tomorrow", "morning", "evening", "night", "later", "earlier", "day", "week", "minute", "minutes", "hour", "need", "needs", "want", "wants", "like", "likes", "love", "prefer", "make", "makes", "made", "get", "gets", "got", "take", "takes", "nobody", "nothing", "everything", "anything", "something", "somewhere", "anywhere", "everywhere", "nowhere", "reading", "sleeping", "working", "guests", "movie", "party", "tv", "ready", "done", "finished", "complete", "sure", "whoever", "whatever", "wherever", "however", "whichever", "ahead", "together", "anyway", "ta", "properly", "cause", "heading", "going", "coming", "leaving", "use", "used", "using", "there", "their", "theyre", "where", "were", "went", "wear", "ware", "think", "thought", "know", "knew", "mean", "meant", "say", "said", "tell", "told", "ask", "asked", "see", "saw", "look", "looks", "looking", "come", "came", "try", "tried", "wait", "feel", "felt", "seem", "seems", "hear", "heard", "remember", "forget", "forgot", "guess", "bother", "worry", "hurry", "rush", "call", "called", "thing", "stuff", "mess", "bit", "lot", "lots", "kind", "sort", "dear", "sweet", "spare", "extra", "remaining", "leftover", "fresh", "new", "used", "empty",
    "other", "big", "biggest", "smaller", "smallest", "larger", "largest", "good", "quick",
    "proper", "thorough", "decent", "nice", "bit", "while", "movie", "film", "show", "night",
    "sleep", "headache", "guest", "visitors", "visitor", "check", "checked", "verify",
    "confirm", "double", "minute", "minutes", "second", "seconds", "couple", "while",
    "charge", "corner", "wall"])

#: fixed expressions, rewritten before tagging (regular expressions on normalised text)
IDIOMS: tuple[tuple[str, str], ...] = (
    (r"\bget rid of\b", "discard"),
    (r"\bdo (?:the|all the) (?:dishes|washing up)\b", "wash the dishes"),
    (r"\bdo the washing up\b", "wash the dishes"),
    (r"\blights? out\b", "lights off"),
    (r"\b(?:switch|turn|flip|flick) (?:the )?lights? (?:on|off) and (?:on|off)\b", "toggle the light"),
    (r"\bmake (?:a |some |the )?(?:cup|mug|pot) of coffee\b", "make coffee"),
    (r"\bbrew (?:a |some )?coffee\b", "make coffee"),
    (r"\bwould you mind\b", "please"),
    # "we're out of loo roll on the holder": what has run out is missing from its place
    (r"\b(?:we|i) (?:are|am|have|have run|ran|run|have just run) (?:all )?out of\b", "there is no"),
    # daylight comes in through the blinds
    (r"\blet (?:some |more |the |a bit of |a little )?(?:natural |day|sun|)(?:light|sunlight|"
     r"sunshine) in\b", "open the blinds"),
)

#: chores with no single household reading: an instruction with one of them is refused
#: with a clear message rather than guessed at
VAGUE_PHRASES: tuple[str, ...] = (
    r"\b(?:set|lay|clear) (?:the |up the )?table\b",
    r"\bdo (?:the |some )?(?:chores|laundry|housework|cleaning|dishes later)\b",
    r"\b(?:tidy|clean|straighten|sort) (?:up|out)?\s*(?:the |this |my )?(?:room|house|place|kitchen|bedroom|bathroom|living room|mess)\b",
)

#: a recipe: a dish whose household reading is clear
RECIPES: dict[str, str] = {
    "coffee": "coffee", "espresso": "coffee", "latte": "coffee", "cappuccino": "coffee",
    "americano": "coffee", "toast": "toast", "slice of toast": "toast", "salad": "salad",
    "fried egg": "egg", "poached egg": "egg", "hard boiled egg": "egg", "soft boiled egg": "egg",
    "jacket potato": "potato", "roast potato": "potato", "boiled potato": "potato",
    "boiled egg": "egg", "scrambled egg": "egg", "omelette": "egg", "omelet": "egg",
    "baked potato": "potato", "fries": "potato", "chips": "potato", "mashed potato": "potato",
}

#: meals and chores with no single household reading: a clear error instead of a guess
VAGUE_NOUNS = frozenset({"dinner", "lunch", "breakfast", "supper", "meal", "brunch", "snack",
                         "food", "mess", "laundry", "chores", "room", "house", "kitchen",
                         "bedroom", "bathroom", "living room", "place", "table"})

LIQUIDS = frozenset({"water", "coffee", "wine"})


@dataclass(frozen=True, slots=True)
class Concept:
    """What a noun names: object types (in order of preference), with fallbacks for
    scenes that lack all of them."""

    name: str
    types: tuple[str, ...] = ()
    fallback: tuple[str, ...] = ()
    kind: str = "object"   # object | category | lights | lamps | room | liquid | anything | recipe

    @property
    def is_category(self) -> bool:
        return self.kind == "category"


def _obj(*types: str, fallback: tuple[str, ...] = ()) -> Concept:
    return Concept(split_camel(types[0]).lower(), types, fallback)


def _cat(name: str, *types: str) -> Concept:
    return Concept(name, types, kind="category")


_VEG = _cat("vegetables", "Lettuce", "Potato", "Tomato")
_FRUIT = _cat("fruit", "Apple")
_PRODUCE = _cat("produce", "Apple", "Lettuce", "Potato", "Tomato")
_FOOD = _cat("food", "Apple", "Bread", "Egg", "Lettuce", "Potato", "Tomato")
_DISHES = _cat("dishes", "Plate", "Bowl", "Cup", "Mug")
_COOKWARE = _cat("cookware", "Pan", "Pot", "Kettle")
_CUTLERY = _cat("cutlery", "Fork", "Spoon", "Knife", "ButterKnife")
_UTENSILS = _cat("utensils", "Fork", "Spoon", "Knife", "ButterKnife", "Spatula", "Ladle")
_ELECTRONICS = _cat("electronics", "Television", "Laptop", "CellPhone", "Desktop")
_APPLIANCES = _cat("appliances", "Microwave", "Toaster", "CoffeeMachine", "Fridge")
_HEATERS = _cat("heating appliance", "Microwave", "StoveBurner", "Toaster")
_SPORTS = _cat("sports equipment", "BaseballBat", "BasketBall", "TennisRacket", "Dumbbell")
_STATIONERY = _cat("stationery", "Pen", "Pencil")
_DECOR = _cat("decorations", "Statue", "Vase", "RoomDecor", "TableTopDecor")
_SEASONING = _cat("condiments", "SaltShaker", "PepperShaker")
_TOWELS = _cat("towels", "Towel", "HandTowel")
_CLEANING = _cat("cleaning supplies", "DishSponge", "SprayBottle", "ScrubBrush", "Cloth",
                 "SoapBottle")
_TOYS = _cat("toys", "TeddyBear", "BasketBall")
_SEATS = _cat("seats", "Sofa", "ArmChair", "Chair", "Stool", "Ottoman")
_TABLES = _cat("tables", "DiningTable", "CoffeeTable", "SideTable", "Desk")
_CONTAINERS = _cat("containers", "Bowl", "Cup", "Mug", "Pot", "Pan", "Box")
_VALUABLES = _cat("valuables", "Watch", "CreditCard", "KeyChain", "CellPhone")
_TOILETRIES = _cat("toiletries", "SoapBar", "SoapBottle", "ToiletPaper")
_HOLDERS = _cat("holder", "TowelHolder", "HandTowelHolder", "ToiletPaperHanger")
_LIGHTS = Concept("lights", ("LightSwitch",), kind="lights")
_LAMPS = Concept("lamp", ("DeskLamp", "FloorLamp"), kind="lamps")
_ROOM = Concept("room", kind="room")
_ANY = Concept("everything", kind="anything")

_NOUNS: dict[str, Concept] = {
    # regional words and nicknames (round 25 of the blind development sets)
    "chiller": _obj("Fridge"), "vino": _obj("WineBottle"), "plonk": _obj("WineBottle"),
    "bottle of plonk": _obj("WineBottle"), "bottle of vino": _obj("WineBottle"),
    "beaker": _obj("Mug", fallback=("Cup",)), "strongbox": _obj("Safe"), "strong box": _obj("Safe"),
    "press": _obj("Cabinet"), "zapper": _obj("RemoteControl"), "biro": _obj("Pen"),
    "facecloth": _obj("Cloth"), "face cloth": _obj("Cloth"), "flannel": _obj("Cloth"),
    "wash basket": _obj("LaundryHamper"),
    "wastepaper basket": _obj("GarbageCan"), "waste paper basket": _obj("GarbageCan"),
    "mixer tap": _obj("Faucet"), "floor light": _obj("FloorLamp"),
    "benchtop": _obj("CounterTop"), "bench top": _obj("CounterTop"), "lounge": _obj("Sofa"),
    "blade": _obj("Knife", fallback=("ButterKnife",)),
    # --- categories
    **{w: _VEG for w in ("vegetable", "veggie", "veg", "veggy", "greens")},
    **{w: _FRUIT for w in ("fruit",)},
    **{w: _PRODUCE for w in ("produce", "fruit and vegetable", "fruit and veggie")},
    **{w: _FOOD for w in ("food item", "grocery", "groceries", "ingredient", "perishable",
                          "food")},
    **{w: _DISHES for w in ("dishware", "crockery", "tableware", "dinnerware")},
    **{w: _COOKWARE for w in ("cookware", "pots and pan", "pot and pan")},
    **{w: _CUTLERY for w in ("cutlery", "silverware", "flatware")},
    **{w: _UTENSILS for w in ("utensil", "kitchen utensil", "kitchenware")},
    **{w: _ELECTRONICS for w in ("electronic", "electronics", "device", "gadget",
                                 "electronic device")},
    **{w: _APPLIANCES for w in ("appliance", "kitchen appliance")},
    **{w: _HEATERS for w in ("heating appliance", "heat source", "heater", "heating device",
                             "cooking appliance")},
    **{w: _SPORTS for w in ("sports equipment", "sport equipment", "sports gear",
                            "sports item", "exercise equipment")},
    **{w: _STATIONERY for w in ("stationery", "writing utensil", "writing tool",
                                "writing implement")},
    **{w: _DECOR for w in ("decoration", "decor", "ornament", "knick knack", "trinket")},
    **{w: _SEASONING for w in ("condiment", "seasoning", "spice", "salt and pepper",
                               "shaker")},
    **{w: _TOWELS for w in ("towels",)},
    **{w: _CLEANING for w in ("cleaning supply", "cleaning supplies", "cleaning product",
                              "cleaning tool")},
    **{w: _TOYS for w in ("toy",)},
    **{w: _SEATS for w in ("seat", "seating")},
    **{w: _CONTAINERS for w in ("container", "receptacle", "vessel")},
    **{w: _VALUABLES for w in ("valuable", "valuables", "personal item", "belonging",
                               "belongings")},
    **{w: _TOILETRIES for w in ("toiletry", "toiletries")},
    **{w: _HOLDERS for w in ("holder", "hanger", "rack", "rail")},
    # --- lights, rooms, everything
    **{w: _LIGHTS for w in ("light", "lights", "lighting", "overhead light", "ceiling light",
                            "main light", "room light", "light fixture", "illumination", "big light")},
    **{w: _LAMPS for w in ("lamp",)},
    **{w: _ROOM for w in ("room", "kitchen", "living room", "lounge", "bedroom", "bathroom",
                          "restroom", "house", "home", "area", "space", "place", "apartment",
                          "flat", "den", "office", "study")},
    **{w: _ANY for w in ("everything", "item", "object", "stuff", "thing")},
    # --- kitchen
    "fridge": _obj("Fridge"), "refrigerator": _obj("Fridge"), "freezer": _obj("Fridge"),
    # "the fridge door": opening and closing the door is opening and closing the fridge
    "fridge door": _obj("Fridge"), "refrigerator door": _obj("Fridge"),
    "freezer door": _obj("Fridge"), "microwave door": _obj("Microwave"),
    "oven door": _obj("Microwave"), "cabinet door": _obj("Cabinet"),
    "cupboard door": _obj("Cabinet"), "box lid": _obj("Box"), "laptop lid": _obj("Laptop"),
    "icebox": _obj("Fridge"), "refrigirator": _obj("Fridge"), "frig": _obj("Fridge"),
    "microwave oven": _obj("Microwave"), "oven": _obj("Microwave"),
    "coffee maker": _obj("CoffeeMachine"), "coffeemaker": _obj("CoffeeMachine"),
    "espresso machine": _obj("CoffeeMachine"), "coffee pot": _obj("CoffeeMachine"),
    "stove": _obj("StoveBurner"), "stovetop": _obj("StoveBurner"), "stove top": _obj("StoveBurner"),
    "burner": _obj("StoveBurner"), "hob": _obj("StoveBurner"), "cooktop": _obj("StoveBurner"), "ring": _obj("StoveBurner"),
    "range": _obj("StoveBurner"), "gas": _obj("StoveBurner"), "cooker": _obj("StoveBurner"),
    "knob": _obj("StoveKnob"), "stove knob": _obj("StoveKnob"), "dial": _obj("StoveKnob"),
    "faucet": _obj("Faucet"), "tap": _obj("Faucet"), "spigot": _obj("Faucet"),
    "sink": _obj("SinkBasin", fallback=("Sink",)), "basin": _obj("SinkBasin", fallback=("BathtubBasin",)),
    "kitchen sink": _obj("SinkBasin", fallback=("Sink",)),
    "washbasin": _obj("SinkBasin", fallback=("Sink",)),
    "counter": _obj("CounterTop"), "countertop": _obj("CounterTop"),
    "kitchen counter": _obj("CounterTop"), "worktop": _obj("CounterTop"),
    "work surface": _obj("CounterTop"), "bench": _obj("CounterTop"), "island": _obj("CounterTop"),
    "kitchen island": _obj("CounterTop"), "vanity": _obj("CounterTop"),
    "table": _obj("DiningTable", "CoffeeTable", fallback=("SideTable", "Desk", "CounterTop")),
    "kitchen table": _obj("DiningTable"), "dinner table": _obj("DiningTable"),
    "dining room table": _obj("DiningTable"),
    "cupboard": _obj("Cabinet"), "kitchen cabinet": _obj("Cabinet"), "closet": _obj("Cabinet"),
    "pantry": _obj("Cabinet"),
    "frying pan": _obj("Pan"), "skillet": _obj("Pan"), "frypan": _obj("Pan"), "wok": _obj("Pan"),
    "saucepan": _obj("Pot"), "cooking pot": _obj("Pot"), "stockpot": _obj("Pot"),
    "kettle": _obj("Kettle"), "teapot": _obj("Kettle"), "tea kettle": _obj("Kettle"),
    "dish": _obj("Plate"), "plate": _obj("Plate"), "dinner plate": _obj("Plate"),
    "saucer": _obj("Plate"), "platter": _obj("Plate"),
    "coffee mug": _obj("Mug"), "coffee cup": _obj("Mug"), "tea cup": _obj("Mug", "Cup"),
    "teacup": _obj("Mug", "Cup"),
    "glass": _obj("Cup"), "tumbler": _obj("Cup"), "drinking glass": _obj("Cup"),
    "teaspoon": _obj("Spoon"), "tablespoon": _obj("Spoon"), "turner": _obj("Spatula"),
    "knife": _obj("Knife", fallback=("ButterKnife",)), "kitchen knife": _obj("Knife"),
    "chef knife": _obj("Knife"), "bread knife": _obj("Knife"), "sharp knife": _obj("Knife"),
    "salt": _obj("SaltShaker"), "saltshaker": _obj("SaltShaker"),
    "pepper": _obj("PepperShaker"), "pepper mill": _obj("PepperShaker"),
    "pepper grinder": _obj("PepperShaker"),
    "loaf": _obj("Bread"), "bread loaf": _obj("Bread"), "breadloaf": _obj("Bread"),
    "loaf of bread": _obj("Bread"), "baguette": _obj("Bread"),
    "toast": _obj("BreadSliced"), "slice of toast": _obj("BreadSliced"),
    "spud": _obj("Potato"), "tater": _obj("Potato"),
    "bottle": _obj("Bottle", fallback=("WineBottle", "SoapBottle", "SprayBottle")),
    "water bottle": _obj("Bottle"), "bottle of wine": _obj("WineBottle"),
    "wine": _obj("WineBottle"),
    "foil": _obj("AluminumFoil"), "aluminium foil": _obj("AluminumFoil"),
    "tin foil": _obj("AluminumFoil"), "tinfoil": _obj("AluminumFoil"),
    "paper towel": _obj("PaperTowelRoll"), "kitchen roll": _obj("PaperTowelRoll"),
    "paper towel roll": _obj("PaperTowelRoll"), "roll of paper towel": _obj("PaperTowelRoll"),
    "sponge": _obj("DishSponge"), "dishsponge": _obj("DishSponge"),
    "washing up sponge": _obj("DishSponge"),
    "scrubber": _obj("DishSponge", "ScrubBrush"),
    "dish soap": _obj("SoapBottle"), "hand soap": _obj("SoapBottle"),
    "soap dispenser": _obj("SoapBottle"), "liquid soap": _obj("SoapBottle"),
    "detergent": _obj("SoapBottle"), "dishwashing liquid": _obj("SoapBottle"),
    "soap": _obj("SoapBar", fallback=("SoapBottle",)), "bar of soap": _obj("SoapBar"),
    "soapbar": _obj("SoapBar"),
    "spray": _obj("SprayBottle"), "cleaner": _obj("SprayBottle"),
    "cleaning spray": _obj("SprayBottle"), "spray cleaner": _obj("SprayBottle"),
    "plant": _obj("HousePlant"), "houseplant": _obj("HousePlant"),
    "potted plant": _obj("HousePlant"), "flower": _obj("HousePlant"),
    "flower pot": _obj("HousePlant"), "pot plant": _obj("HousePlant"),
    "trash can": _obj("GarbageCan"), "trashcan": _obj("GarbageCan"), "trash": _obj("GarbageCan"),
    "garbage": _obj("GarbageCan"), "bin": _obj("GarbageCan"), "trash bin": _obj("GarbageCan"),
    "waste basket": _obj("GarbageCan"), "wastebasket": _obj("GarbageCan"),
    "dustbin": _obj("GarbageCan"), "rubbish": _obj("GarbageCan"),
    "rubbish bin": _obj("GarbageCan"), "waste bin": _obj("GarbageCan"),
    "recycling bin": _obj("GarbageCan"), "recycle bin": _obj("GarbageCan"),
    "garbage bin": _obj("GarbageCan"), "wastebin": _obj("GarbageCan"),
    "trash bag": _obj("GarbageBag"), "bin bag": _obj("GarbageBag"),
    # --- living room, bedroom
    "tv": _obj("Television"), "telly": _obj("Television"), "tee vee": _obj("Television"),
    "picture box": _obj("Television"), "goggle box": _obj("Television"), "tv set": _obj("Television"),
    "television set": _obj("Television"), "screen": _obj("Television"),
    "remote": _obj("RemoteControl"), "tv remote": _obj("RemoteControl"),
    "clicker": _obj("RemoteControl"), "controller": _obj("RemoteControl"),
    "phone": _obj("CellPhone"), "mobile": _obj("CellPhone"), "mobile phone": _obj("CellPhone"),
    "smartphone": _obj("CellPhone"), "cell": _obj("CellPhone"), "iphone": _obj("CellPhone"),
    "cellphone": _obj("CellPhone"),
    "computer": _obj("Laptop", "Desktop"), "notebook": _obj("Laptop"),
    "notebook computer": _obj("Laptop"), "macbook": _obj("Laptop"), "pc": _obj("Desktop", "Laptop"),
    "desktop computer": _obj("Desktop"), "monitor": _obj("Desktop", "Television"),
    "couch": _obj("Sofa"), "settee": _obj("Sofa"), "loveseat": _obj("Sofa"),
    "arm chair": _obj("ArmChair"), "recliner": _obj("ArmChair"),
    "ottoman": _obj("Ottoman", "Footstool"), "footstool": _obj("Footstool", "Ottoman"),
    "foot stool": _obj("Footstool", "Ottoman"), "pouf": _obj("Ottoman", "Footstool"),
    "footrest": _obj("Ottoman", "Footstool"),
    "chair": _obj("Chair", fallback=("ArmChair", "Stool")),
    "stool": _obj("Stool", fallback=("Footstool",)), "bar stool": _obj("Stool"),
    "nightstand": _obj("SideTable"), "night stand": _obj("SideTable"),
    "bedside table": _obj("SideTable"), "end table": _obj("SideTable"),
    "night table": _obj("SideTable"), "side table": _obj("SideTable"),
    "chest of drawer": _obj("Dresser"), "chest": _obj("Dresser"),
    "tv stand": _obj("TVStand"), "tv table": _obj("TVStand"), "tv cabinet": _obj("TVStand"),
    "media console": _obj("TVStand"), "entertainment center": _obj("TVStand"),
    "shelf": _obj("Shelf", fallback=("ShelvingUnit",)),
    "bookshelf": _obj("ShelvingUnit", "Shelf"), "bookcase": _obj("ShelvingUnit", "Shelf"),
    "shelving": _obj("ShelvingUnit", "Shelf"), "book shelf": _obj("ShelvingUnit", "Shelf"),
    "pillow": _obj("Pillow"), "cushion": _obj("Pillow"),
    "carton": _obj("Box"), "cardboard box": _obj("Box"),
    "tissue": _obj("TissueBox"), "tissue box": _obj("TissueBox"), "kleenex": _obj("TissueBox"),
    "box of tissue": _obj("TissueBox"),
    "clock": _obj("AlarmClock"), "alarm": _obj("AlarmClock"),
    "disc": _obj("CD"), "compact disc": _obj("CD"), "dvd": _obj("CD"), "cd": _obj("CD"),
    "bat": _obj("BaseballBat"), "ball": _obj("BasketBall"), "basketball": _obj("BasketBall"),
    "racket": _obj("TennisRacket"), "racquet": _obj("TennisRacket"),
    "tennis racquet": _obj("TennisRacket"),
    "weight": _obj("Dumbbell"), "dumb bell": _obj("Dumbbell"),
    "teddy": _obj("TeddyBear"), "teddy bear": _obj("TeddyBear"), "stuffed animal": _obj("TeddyBear"),
    "plush": _obj("TeddyBear"), "plush toy": _obj("TeddyBear"), "soft toy": _obj("TeddyBear"),
    "boot": _obj("Boots"), "boots": _obj("Boots"), "shoe": _obj("Boots"),
    "hamper": _obj("LaundryHamper"), "laundry basket": _obj("LaundryHamper"), "basket": _obj("LaundryHamper"),
    "vacuum": _obj("VacuumCleaner"), "hoover": _obj("VacuumCleaner"),
    "picture": _obj("Painting"), "artwork": _obj("Painting"), "frame": _obj("Painting"),
    "blind": _obj("Blinds"), "blinds": _obj("Blinds"), "shade": _obj("Blinds"),
    # AI2-THOR's curtains do not open or close: to draw "the curtains" of a room that has
    # blinds is to close its blinds
    "curtain": _obj("Curtains", "Blinds"), "curtains": _obj("Curtains", "Blinds"),
    "drape": _obj("Curtains", "Blinds"),
    "figurine": _obj("Statue"), "sculpture": _obj("Statue"),
    "book": _obj("Book"), "novel": _obj("Book"), "textbook": _obj("Book"),
    "paper": _obj("Newspaper"), "magazine": _obj("Newspaper"),
    "card": _obj("CreditCard"), "bank card": _obj("CreditCard"), "debit card": _obj("CreditCard"),
    "key": _obj("KeyChain"), "keys": _obj("KeyChain"), "key ring": _obj("KeyChain"),
    "keyring": _obj("KeyChain"), "set of key": _obj("KeyChain"),
    "wristwatch": _obj("Watch"), "desk light": _obj("DeskLamp"), "table lamp": _obj("DeskLamp"),
    "reading lamp": _obj("DeskLamp", "FloorLamp"), "bedside lamp": _obj("DeskLamp"),
    "standing lamp": _obj("FloorLamp"), "lamp post": _obj("FloorLamp"),
    # a lamp by its size: a floor lamp is the big one, a desk lamp the little one
    "big lamp": _obj("FloorLamp", fallback=("DeskLamp",)), "tall lamp": _obj("FloorLamp", fallback=("DeskLamp",)),
    "standard lamp": _obj("FloorLamp"), "little lamp": _obj("DeskLamp", fallback=("FloorLamp",)),
    "small lamp": _obj("DeskLamp", fallback=("FloorLamp",)),
    "switch": _obj("LightSwitch"), "light switch": _obj("LightSwitch"),
    "watering can": _obj("WateringCan"),
    "dog bed": _obj("DogBed"), "pet bed": _obj("DogBed"),
    # --- bathroom
    "bathtub": _obj("BathtubBasin", fallback=("Bathtub",)),
    "tub": _obj("BathtubBasin", fallback=("Bathtub",)),
    "bath": _obj("BathtubBasin", fallback=("Bathtub",)),
    "bath tub": _obj("BathtubBasin", fallback=("Bathtub",)),
    "shower": _obj("ShowerHead"), "showerhead": _obj("ShowerHead"),
    "shower head": _obj("ShowerHead"),
    "loo": _obj("Toilet"), "wc": _obj("Toilet"), "commode": _obj("Toilet"),
    "toilet roll": _obj("ToiletPaper"), "loo roll": _obj("ToiletPaper"), "loo paper": _obj("ToiletPaper"),
    "toilet tissue": _obj("ToiletPaper"), "bog roll": _obj("ToiletPaper"), "tp": _obj("ToiletPaper"),
    "bathroom tissue": _obj("ToiletPaper"), "roll of toilet paper": _obj("ToiletPaper"),
    "toilet paper roll": _obj("ToiletPaper"),
    "toilet paper holder": _obj("ToiletPaperHanger"),
    "toilet roll holder": _obj("ToiletPaperHanger"), "paper holder": _obj("ToiletPaperHanger"),
    "toilet paper hanger": _obj("ToiletPaperHanger"),
    "bath towel": _obj("Towel"), "hand towel holder": _obj("HandTowelHolder"),
    "hand towel rack": _obj("HandTowelHolder"), "hand towel ring": _obj("HandTowelHolder"),
    "towel rack": _obj("TowelHolder"), "towel rail": _obj("TowelHolder"),
    "towel bar": _obj("TowelHolder"), "towel ring": _obj("TowelHolder"),
    "towel hanger": _obj("TowelHolder"),
    "toilet brush": _obj("ScrubBrush"), "brush": _obj("ScrubBrush"),
    "scrub brush": _obj("ScrubBrush"), "scrubbing brush": _obj("ScrubBrush"),
    "rag": _obj("Cloth"), "washcloth": _obj("Cloth"), "wash cloth": _obj("Cloth"),
    "dishcloth": _obj("Cloth", "DishSponge"), "dish cloth": _obj("Cloth", "DishSponge"),
    "cloth": _obj("Cloth"), "towel": _obj("Towel", fallback=("HandTowel",)),
    "roll": _obj("ToiletPaper", fallback=("PaperTowelRoll",)),
    "ground": _obj("Floor"),
}

#: plural forms that mean something else than their singular ("dishes" = all dishware)
PLURAL_NOUNS: dict[str, Concept] = {
    "dishes": _DISHES, "shelves": _obj("Shelf", "ShelvingUnit"), "glasses": _obj("Cup"),
    "towels": _TOWELS, "things": _ANY, "items": _ANY, "objects": _ANY,
    "supplies": _CLEANING, "salt and pepper shakers": _SEASONING, "shakers": _SEASONING,
    "lights": _LIGHTS, "tables": _TABLES, "knives": _obj("Knife", "ButterKnife"),
    # the type names are plural, the words too: "the blinds" are all of them
    "blinds": _obj("Blinds"), "curtains": _obj("Curtains", "Blinds"), "shades": _obj("Blinds"),
    "drapes": _obj("Curtains", "Blinds"),
}

#: measure and collective words: "a roll of foil", "two loaves of bread", "a head of
#: lettuce", "a pair of boots" name the thing after "of"
MEASURE_WORDS = frozenset({
    "roll", "rolls", "loaf", "loaves", "bar", "bars", "head", "heads", "pair", "pairs",
    "bunch", "bunches", "packet", "packets", "pack", "packs", "stick", "sticks", "sheet",
    "sheets", "stack", "stacks", "pile", "piles"})

#: "a plate containing an egg": the words that introduce what a container holds
CONTAINING = frozenset({"containing", "contains", "holding", "carrying"})

#: collective nouns of categories: "the cutlery" is every piece of cutlery
MASS_NOUNS = frozenset({
    "sports equipment", "sport equipment", "sports gear", "exercise equipment", "cutlery",
    "silverware", "flatware", "produce", "food", "groceries", "electronics", "decor",
    "dishware", "crockery", "tableware", "dinnerware", "cookware", "kitchenware",
    "stationery", "seating", "toiletries", "cleaning supplies", "valuables", "belongings",
    "fruit and vegetable", "fruit and veggie", "salt and pepper"})

#: what is switched instead of an object that cannot be (the stove by its knobs)
SWITCHED_BY: dict[str, tuple[str, ...]] = {
    "StoveBurner": ("StoveKnob",), "Sink": ("Faucet",), "SinkBasin": ("Faucet",),
    "Bathtub": ("Faucet", "ShowerHead"), "BathtubBasin": ("Faucet", "ShowerHead"),
    "Desk": ("DeskLamp",), "Floor": ("FloorLamp",),
}

#: robot words: "robot 2", "the second robot", "bot 3"
ROBOT_WORDS = frozenset({"robot", "bot", "agent", "r", "unit"})


@cache
def nouns() -> dict[str, Concept]:
    """All noun phrases (singular), hand-written synonyms first, then every catalogue type
    by its own name, split and run together."""
    out = dict(_NOUNS)
    cat = load_catalogue()
    source = {piece for piece, _ in cat.slice_products.values()}
    for name in cat.types:
        if name in source:
            continue
        spaced = split_camel(name).lower()
        for key in (spaced, spaced.replace(" ", "")):
            out.setdefault(key, _obj(name))
    out.setdefault("tv stand", _obj("TVStand"))
    _add_compound_heads(out, cat.types, source)
    return out


def _add_compound_heads(out: dict[str, Concept], types: Iterable[str], source: set[str]) -> None:
    """"Put the mug in the coffee machine and switch the machine on": the last word of a
    compound type name ("machine", "control", "chain") names that type when the word means
    nothing else to the parser; several types sharing the word are one concept (the
    grounder keeps those in the scene)."""
    reserved = COMMON_WORDS | ROBOT_WORDS | MEASURE_WORDS | PARTICLES | set(VERBS) | set(STATES)
    heads: dict[str, list[str]] = {}
    for name in types:
        words = split_camel(name).lower().split()
        if len(words) > 1 and name not in source:
            heads.setdefault(words[-1], []).append(name)
    for word, named in sorted(heads.items()):
        if word not in out and word not in reserved:
            out[word] = Concept(word, tuple(sorted(named)))


@cache
def noun_words() -> frozenset[str]:
    """Every word that occurs in a noun phrase."""
    words: set[str] = set()
    for phrase in list(nouns()) + list(PLURAL_NOUNS) + list(RECIPES):
        words.update(phrase.split())
    return frozenset(words)


@cache
def vocabulary() -> frozenset[str]:
    """Every word the parser knows: the targets of spelling correction."""
    words = set(noun_words()) | set(VERBS) | set(STATES) | set(PARTICLES) | set(NUMBERS)
    words |= {w for p in PREPOSITIONS for w in p.split()}
    words |= {w for p in SEQUENCE_MARKERS for w in p.split()}
    words |= set(LIQUIDS) | set(IRREGULAR_VERBS) | DETERMINERS | QUANTIFIERS | PRONOUNS
    words |= NEGATIONS | COPULAS | set(ORDINALS) | ROBOT_WORDS | COMMON_WORDS | CONTAINING
    words |= MEASURE_WORDS
    words |= {verb for verb, _ in PARTICLE_VERBS}      # "fire (up)" is no typo of "file"
    return frozenset(words)


#: content words spelling correction may produce (never a function word: "there" must
#: not become "three")
@cache
def correction_targets(nouns_only: bool = False) -> frozenset[str]:
    words = set(noun_words()) | set(LIQUIDS)
    if not nouns_only:
        words |= set(VERBS) | set(STATES) | CONTAINING
    return frozenset(w for w in words if len(w) >= 3) - COMMON_WORDS

