"""Steps said in one breath, cut where the order they are done in is said (`intent.read_request`
reads each part): "give Anna a ring once you've made it to the bedroom", "switch the projector
off before you head to the bedroom", "call Clara after you put the projector on", "once you're
in the kitchen video call Clara"; and two steps joined by "and" after a "but first" before both
("call the doctor, but first go to the living room and switch the projector on")."""

from __future__ import annotations

import re

from robovoice.assistant.clause_kind import classify
from robovoice.assistant.hypothetical import AFTER_YOU_DID, ARRIVED, BEFORE_YOU_DO, ONCE_THERE
from robovoice.assistant.reading import ClauseKind

# "…, but come into the living room before you do": before the request said just before (text test v51)
_BEFORE_YOU_DO_IT = re.compile(r"\s+before you do(?: (?:it|that|so))?\s*$", re.IGNORECASE)
# "once you're in the kitchen video call Clara" with no comma (text test v60): being there, then the
# request; the place one or two words ("the living room")
_ONCE_IN = re.compile(r"^((?:once|as soon as) you(?:'re| are) (?:in|at|by|inside) (?:the|my|your) (\w+)(?: (\w+))?)"
                      r"\s+(.+)$", re.IGNORECASE)


_COURTESY_LAST = re.compile(r"(?:,?\s+(?:please|thanks|thank you))+\s*$", re.IGNORECASE)


def first_both(parts: list[str], text: str) -> list[str]:
    """A request, then "but first A and B": A and B, then the request (text tests v129 and v130:
    "I'm wanting to speak to Doctor Weber, but first go to the bedroom and switch the projector on"
    put only A first, and the call before B). Only two requests joined by a bare "and" as said."""
    for i in range(1, len(parts) - 1):
        first, then = parts[i].strip(), parts[i + 1].strip()
        if _FIRST_OPENS.match(first) and re.search(re.escape(first) + r"\s+and\s+" + re.escape(then), text) \
                and not _ORDERED.search(then) and all(classify(p) is ClauseKind.REQUEST
                                                      for p in (parts[i - 1], first, then)):
            return [*parts[:i - 1], parts[i], parts[i + 1], parts[i - 1], *parts[i + 2:]]
    return parts


_FIRST_OPENS = re.compile(r"^(?:but |and |so )?first\b", re.IGNORECASE)
_ORDERED = re.compile(r"\b(?:first|then|after|afterwards|before|once|when)\b", re.IGNORECASE)
# a state only the robot brings about, said as the time for what follows: "Once the projector's on,
# ring Anna so she can watch with us" (text test v134) is the switch, then the call
_ONCE_SWITCHED = re.compile(r"^(?:once|as soon as) (?:the|your) projector(?:'s| is) (on|off)$", re.IGNORECASE)


def switched_first(parts: list[str]) -> list[str]:
    """An utterance opening on "once the projector's on," before a request: that switch first."""
    if len(parts) > 1 and (state := _ONCE_SWITCHED.match(parts[0].strip())) \
            and classify(parts[1]) is ClauseKind.REQUEST:
        return [f"switch the projector {state.group(1).lower()}", *parts[1:]]
    return parts


def arrival_first(parts: list[str]) -> list[str]:
    """A request that ends on where the robot will have got to ("give Anna a ring once you've
    made it to the bedroom") as two clauses in the order said: the arrival (a `SEQUENCE`
    clause, which goes first) after the request; one that ends on what it does next ("switch
    the projector off before you head to the bedroom") as that request, then the next; one that
    begins on where it will be, with no comma, as that and the request."""
    out: list[str] = []
    moved = False  # the part before was a "once you're in the kitchen" put first
    for i, part in enumerate(parts):
        if moved and _NOT_BEFORE.match(part.strip()):
            continue  # "…, but only once you're in the kitchen, not before": said again, not a time held
        after = [p for p in parts[i + 1:] if not _NOT_BEFORE.match(p.strip())][:1]
        moved = bool(ONCE_THERE.match(part.strip()) and out and classify(out[-1]) is ClauseKind.REQUEST and (
            part.strip().lower().startswith("only") or not any(classify(p) is ClauseKind.REQUEST for p in after)))
        if moved:  # "Call Clara, but only once you're in the kitchen": being there first (text test v93)
            out.insert(len(out) - 1, part)
            continue
        if (first := _BEFORE_YOU_DO_IT.search(part)) and out and \
                classify(part[:first.start()]) is ClauseKind.REQUEST and classify(out[-1]) is ClauseKind.REQUEST:
            out.insert(len(out) - 1, part[:first.start()])  # "ring him, but come here before you do"
            continue
        if (there := _ONCE_IN.match(part)) is not None and (cut := _once_in(there)) is not None:
            out += cut
            continue
        if ARRIVED.search(bare := _COURTESY_LAST.sub("", part)):
            part = bare  # "call anna after you get to the living room please" (text test v118)
        late = ARRIVED.search(part) or BEFORE_YOU_DO.search(part) or AFTER_YOU_DID.search(part)
        if late is not None and classify(part[:late.start()]) is ClauseKind.REQUEST:  # "once you're in X": X first
            # (text test v57; said in the present, "… after you get to the bedroom": text test v71)
            there_first = re.match(r"\w+ you(?:'re| are| get| arrive| reach| make it| go| come| head| drive) ",
                                   late.group(1)) is not None
            out += [late.group(1), part[:late.start()]] if there_first else [part[:late.start()], late.group(1)]
        else:
            out.append(part)
    return out


def _once_in(there: re.Match[str]) -> list[str] | None:
    """"once you're in the kitchen" and the request after it; the place is two words when its
    second is a kind of place ("the living room", "the front door")."""
    whole, second, rest = there.group(1), there.group(3), there.group(4)
    if second is not None and second.lower() in _PLACE_NOUNS:
        return [whole, rest] if classify(rest) is ClauseKind.REQUEST else None
    after = f"{second} {rest}" if second is not None else rest
    if classify(after) is ClauseKind.REQUEST:
        return [whole[:len(whole) - len(second)].rstrip() if second is not None else whole, after]
    return None


_NOT_BEFORE = re.compile(r"^(?:and |but )?not (?:before|until then|till then)\W*$", re.IGNORECASE)
_PLACE_NOUNS = frozenset({"room", "door", "dock", "station", "hall", "way", "area", "corner"})
