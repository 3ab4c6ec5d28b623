"""Swahili (and Sheng, Nairobi's street Swahili) inside English speech: the requests, order
words, negations and rooms put in English, for the reading only (text test v83: "piga simu
Uncle Ben", "toka hapa uende bedroom", "Zima projector, alafu uende kitchen", "kata hiyo call"
were talk or did one thing).

Swahili says the verb first, as English does, so most rules only put a word in English. Its
negative is a prefix ("usiende": don't go, "usipige simu": don't call); "unaweza …?" asks what
the robot can do. Nothing is rewritten unless a word only Swahili has was said (`_MARKER`):
"kata", "sema" and "na" could be names or English.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite, rules

_MARKER = re.compile(r"\b(?:tafadhali|halafu|alafu|kisha|kwanza|uende|nenda|enda|kwenda|ende|piga|simu|mpigie|"
                     r"nipigie|washa|zima|hiyo|hii|sasa|hapa|hapo|usi(?!ng?\b)\w{2,}|unaweza|ebu|hebu|haraka|kwenye|"
                     r"mpaka|hadi|jikoni|chumbani|bafuni|sebuleni|asante|sawa|rudi|urudi|njoo|uje|chaji|kuchaji|"
                     r"ukachaji|"
                     r"baadaye|kesho|bado|hapana|ndio|ndiyo|maze|niaje|msee|buda|manze|elekea|uelekee|ingia|simama|"
                     r"subiri|ngoja|maliza|nataka|tafadhalini|shangazi|mjomba|naomba|projekta|wacha|iwashe|kuja)\b",
                     re.IGNORECASE)

_PLACES = r"(?:living room|front door|charging dock|kitchen|bedroom|bathroom|hallway)"
_SOMEWHERE = r"(?=\s+(?!(?:sasa|tu|hapa|hapo|basi|haraka)\b)\w)"  # a place said after the verb
_TO = r"(?:\s+(?:kwa|kwenye|mpaka|hadi|pale|ndani\s+ya|huko|hapo|kule))*"
_GO_WORDS = r"(?:nenda|enda|uende|ende|kaende|kwenda|elekea|uelekee|ukaende|genda|dunda)"  # genda: Luganda
_GO = r"\b" + _GO_WORDS + r"\b"
_COME = r"\b(?:njoo|uje|kuja|ukuje|jangu)\b"  # kuja ("to come") is said for "come!" too; jangu: Luganda
_BACK = r"\b(?:rudi|urudi|kurudi|rudia)\b"
_CALL = (r"\b(?:(?:ku)?piga\s+(?:video\s+call|video|simu)(?:\s+ya\s+video)?(?:\s+(?:kwa|na))?|m?pigie(?:\s+simu)?|"
         r"u?(?:ni|m|wa)?pigi[ae](?:\s+simu)?|kupigia(?:\s+simu)?)\b")
_WHO_TITLE = r"(?:(?:mama|baba|shangazi|mjomba|bibi|babu|dada|kaka|daktari|dokta|auntie|aunty|uncle)\s+)"

_RULES = rules((
    # "unaweza …?": can you …? ("je," before a question says nothing asked)
    (r"\bje\b,?\s*", ""),
    (r"\bunaweza\s+(?:ku(?=(?:piga|pigia|enda|ja\b|rudi|washa|zima|kata|maliza|ingia|simama|chaji))|"
     r"(?=(?:kwenda|kuja|piga|enda|nenda|rudi|washa|zima|kata)\b))", "can you "),
    (r"\bunaweza\b(?:\s+ku(?=\w))?", "are you able to "),  # a verb this table does not know: what it can do
    (r"\b(?:uko|upo|uko\s+wapi|mko)\s+wapi\b", "where are you"), (r"\bama\b", "or"),
    (r"\bunajua\s+(?:ku(?=\w))?", "do you know how to "),
    # (text test v85) "ungeweza …?" (could you), "kabla ya ku…" (before you …), "ukishafika X" (once you're
    # in X), "ila" (but), "uone kama" (and see if), "achana nayo" (leave it), "ngoja kwanza" (hold on)
    (r"\b(?:ungeweza|ungeza|ungependa)\b(?:\s+ku(?=\w))?", "could you "),
    (r"\bkabla\s+ya\s+ku", "before you "), (r"\bkabla\s+ya\b(?!\s+(?:hapo|hiyo|hayo)\b)", "before"),
    (r"\buki(?:sha)?fika\b(?:\s+(?:kwa|kwenye))?", "once you're in the"), (r"\bila\b", "but"),
    (r"\b(?:u|ka|uka)?(?:one|angalie|cheki)\s+kama\b", ", and check if"), (r"\bkama\b", "if"),
    (r"\b(?:achana|acha)\s+(?:na\s*(?:yo|hiyo|hio)|nayo|hiyo|hio)\b", "leave it"),
    (r"\b(?:ngoja|subiri)\s+(?:kwanza|kidogo)\b", "hold on"),
    (r"\bbaada\s+ya\s+chakula\s+cha\s+(?:mchana|asubuhi)\b", "after lunch"),
    (r"\bbaada\s+ya\s+chakula(?:\s+cha\s+(?:jioni|usiku))?\b", "after dinner"), (r"\bndio\b", ""),
    (r"\bsi\s+(?=(?:the\s+)?" + _PLACES + r"\b)", "not the "), (r"\bgeuza\b", "turn round and"),
    (r"\b(?:ni|u|uni)?unganish\w*(?:\s+(?:video\s+call|simu|call))?\s+(?:na|kwa)\b", "video call"),
    (r"\b(?:hiyo\s+|hii\s+)?safari\s+(?:yako\s+)?(?:i|u|ku)?cancel\w*", "cancel the trip"),
    (r"\b(?:i|u|ku)(cancel|stop|end|switch|call|check)\b", r"\1"), (r"\bfasta\b", "quickly"),
    (r"\bnilipo\b", "where I am"), (r"\bhaya\b", "okay"),
    # (text test v87) "naomba u…" (I ask you to), "wacha tu, si lazima" (leave it, no need), "chap chap",
    # "kabla ya hapo" (before that), "kwanza … pili … mwisho" (first, second, last), "ukimaliza" (then)
    (r"\bnaomba\b", "please"), (r"\b(?:wacha|acha)\s+tu\b", "never mind"), (r"\bsio?\s+lazima\b", "no need"),
    (r"\bchap\s+chap\b", "quickly"), (r"\b(?:lakini\s+)?kabla\s+ya\s+(?:hapo|hiyo|hayo)\b", "but before that"),
    (r"\bpili\b", "then"), (r"\b(?:na\s+)?mwisho\b", "and finally"), (r"\bfanya\s+hivi\s*:?", ""),
    (r"\b(?:alafu|halafu)?\s*ukimaliza\b", " then"), (r"\blakini\b", "but"),
    (r"\b(?:u|ku)?kate\b(?:\s+(?:hiyo|hii))?\s+(?:simu|call)\b", "end the call"),
    (r"\bbinti\s+yangu\b", "my daughter"), (r"\bmwanangu\b", ""),
    # its negative, a prefix: "usiende", "usipige simu Ben", "usiwashe projector", "usikate call"
    (r"\busi(?:ende|elekee|ingie)\b" + _TO, "don't go to the"), (r"\busirudi\b" + _TO, "don't go back to the"),
    (r"\busije\b", "don't come"), (r"\busi(?:pige|mpigie)(?:\s+simu)?(?:\s+(?:kwa|na))?\b", "don't call"),
    (r"\busisimame\b", "don't stop"), (r"\bendelea\b", "keep going"), (r"\b(?:ungoje|usubiri)\b", "wait"),
    (r"\b(?:sepa|hepa)\b\s*", ""),  # Sheng: off you go ("sepa uende front door")
    (r"\busiwashe\b", "don't turn on the"), (r"\busizime\b", "don't turn off the"),
    (r"\busi(?:kate|maliza)\b(?:\s+(?:hiyo|hii))?(?:\s+(?:simu|call)\b)?", "don't end the call"),
    (r"\busi(?!ng?\b)(\w{2,})", r"don't \1"),
    (r"\bsi\s+sasa\b|\bsio\s+sasa\b", "not now"), (r"\bbado\b", "not yet"), (r"\bhapana\b", "no"),
    (r"\bsitaki\b", "I don't want"), (r"\b(?:ni)?nataka\b", "I want"),
    # calls: "piga simu Uncle Ben", "mpigie Anna", "kata hiyo call"
    (_CALL + r"\s*" + _WHO_TITLE + r"?", "call "), (r"\bpiga\s+(?=(?-i:[A-Z]))", "call "),
    (r"\b(?:kata|maliza|zima)\s+(?:hiyo\s+|hii\s+)?(?:call|simu)\b", "end the call"),
    # the projector: "washa projector", "zima hiyo projector"
    (r"\b(?:washa|kuwasha|uwashe|iwashe|wezesha)\b(?:\s+(?:hiyo|hii))?", "turn on the"),
    (r"\b(?:zima|kuzima|uzime|izime)\b(?:\s+(?:hiyo|hii))?", "turn off the"),
    # charging: "uende ukachaji", "enda kuchaji", "rudi kwa chaja"
    (r"\b(?:" + _GO_WORDS + r"\s+)?\b(?:ukachaji|kuchaji|kachaji|uchaji|jichaji|chaji)\b", " go charge"),
    (r"\b(?:chaja|charger)\b", "charging dock"),
    # going: "uende bedroom", "nenda kwa kitchen", "rudi sebuleni", "chill kwa hallway" (Sheng: wait there)
    (_GO + _TO + _SOMEWHERE, "go to the"), (_COME + _TO + _SOMEWHERE, "come to the"),
    (_BACK + _TO + _SOMEWHERE, "go back to the"), (_GO, "go"), (_COME, "come"), (_BACK, "go back"),
    (r"\bingia\b" + _TO, "go into the"), (r"\bchill\s+(?:kwa|kwenye|pale)\b", "go and wait in the"),
    (r"\b(?:toka|ondoka)\s+(?:hapa|hapo)\b", "leave here"), (r"\b(?:simama|stopu)\b", "stop"),
    (r"\b(?:subiri|ngoja)\b", "wait"),
    # order words and time
    (r"\b(?:na\s+)?(?:halafu|alafu|kisha|baada\s+ya\s+(?:hapo|hiyo|hayo))\b", "then"), (r"\bkwanza\b", "first"),
    (r"\bbaadaye\b", "later"), (r"\bkesho\b", "tomorrow"), (r"\b(?:sasa\s+hivi|saa\s+hii|sasa\s+hii)\b", "now"),
    (r"(^|[.!?,]\s*)sasa\b,?", r"\1"), (r"\bharaka(?:\s+sana)?\b", "quickly"), (r"\bpole\s+pole\b", "slowly"),
    (r"\b(?:tafadhali|tafadhalini|ebu|hebu|tafadhari)\b", "please"), (r"\b(?:asante|webale)(?:\s+sana)?\b", "thanks"),
    (r"\bni\s+hayo\s+tu\b|\bbasi\s+tu\b", "that's all"), (r"\b(?:sawa|poa)\b", "okay"),
    (r"\bna\s+(?=(?:go|come|call|turn|then|end|stop|please)\b)", "and "),
    (r"\bya\b", "of"),  # not texting's "you"
))
_ROOMS = {"jikoni": "kitchen", "jiko": "kitchen", "sebuleni": "living room", "sebule": "living room",
          "chumbani": "bedroom", "chumba cha kulala": "bedroom", "bafuni": "bathroom", "chooni": "bathroom",
          "choo": "bathroom", "msalani": "bathroom", "mlangoni": "front door", "mlango wa mbele": "front door",
          "korido": "hallway", "ukumbini": "hallway",
          "projekta": "projector", "projecta": "projector"}  # and the projector as Swahili spells it
_ROOM = re.compile(r"\b(" + "|".join(sorted(_ROOMS, key=len, reverse=True)) + r")\b", re.IGNORECASE)
# what says nothing asked: greetings and Sheng's address words, "hapa"/"hapo" (here, there) left over
_PARTICLES = re.compile(r"\s*\b(?:maze|manze|niaje|msee|buda|mzee|bro|sasa|hapa|hapo|huko|kule|hiyo|hii|tu|ile|yile|"
                        r"hizo|hizi|huyo|bana|banange|aje|aisee|mwanangu|"
                        r"ssebo|nnyabo|mukwano|yo)\b(?=\s*(?:[,.!?]|$|\s))", re.IGNORECASE)


# a part said in Swahili with a verb of its own ("…, inaniumiza macho": it hurts my eyes; "…, amelala":
# she is asleep; "…, nataka kuona …": I want to see …) is talk; left in, it reads as one more thing asked
_TALK = re.compile(r"[^,.;!?\u2026]*\b(?:(?:ni|tu|wa|a|u|m|i|ki|ku|li|ya|zi)(?:na|li|ta|me)\w{3,}|(?:ni)?nataka)\b"
                   r"[^,.;!?\u2026]*", re.IGNORECASE)
_ASKS = re.compile(r"\b(?:go|call|turn|end|stop|switch|don't|please|can|later|tomorrow|uende|nenda|enda|rudi|njoo|"
                   r"piga|\w*pigi[ae]|washa|zima|kata|maliza|usi(?!ng?\b)\w{2,}|tafadhali|ebu|hebu|unaweza|kisha|"
                   r"halafu|alafu)\b",
                   re.IGNORECASE)


def from_swahili(text: str) -> str:
    """`text` with the Swahili or Sheng of a request put in English (unchanged without any)."""
    if not _MARKER.search(text):
        return text
    text = _TALK.sub(lambda m: m.group(0) if _ASKS.search(m.group(0)) else "", text)
    text = _ROOM.sub(lambda m: _ROOMS[m.group(1).lower()], text)
    text = _PARTICLES.sub("", rewrite(text, _RULES))
    # "go to the Ben" (the name after a verb said as a place): no "the"; "the the": one
    text = re.sub(r"\b(to|into|in) the\s+(?!" + _PLACES + r"\b)(?=(?-i:[A-Z]))", r"\1 ", text, flags=re.IGNORECASE)
    text = re.sub(r"\bthe\s+the\b", "the", text, flags=re.IGNORECASE)
    return re.sub(r"^[\s,.!?]+", "", re.sub(r"\s+([,.!?])", r"\1", re.sub(r"  +", " ", text))).strip()
