"""Taglish: the requests, order words, negations and rooms of Tagalog said inside English speech,
in English, for the reading only (text test v75: "pakibukas po yung projector", "punta ka sa
sala tapos buksan mo yung projector", "call mo si Tita Clara tas punta ka sa front door" were
talk or did only one thing; text test v76: "pa-on naman ng projector", "dun ka na lang sa sala",
"bago mo tawagan si Clara, lumapit ka muna dito sa kusina" were talk).

Nothing is rewritten unless a word only Tagalog has was said (`_MARKER`): "sala", "na", "ate"
and "at" are English words too. Then its particles ("po", "naman", "na", "lang", ...), its
pronouns after a verb ("mo", "ka") and the "si" / "kay" before a name are dropped, and what
is left reads as an English request: "go to the living room then turn on the projector".
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite, rules

_MARKER = re.compile(r"\b(?:po|naman|nga|lang|muna|tapos|tas|pagkatapos|saka|kaya|punta|pumunta|balik|bumalik|buksan|"
                     r"paki\w+|(?:pa|i|mag|magpa)-\w+|patayin|pumaroon|magtungo|paandarin|kontakin|ihinto|"
                     r"puntahan|isara|tawagan|tawag|salamat|huwag|wag|mamaya|yung|kwarto|kuwarto|banyo|"
                     r"kusina|pasilyo|sige|diba|daw|silipin|tingnan|sundan|lumapit|pagdating|diretso|ngayon|ayan|kasi|"
                     r"nandun|nandoon|andun|andoon|nandito|andito|uwi|umuwi|daan|dumaan|hinto|huminto|tigil|halika|"
                     r"dayon|unya|pintuan|ako|(?:dun|doon|diyan|dyan|dito)\s+ka)\b",
                     re.IGNORECASE)

# what a verb may carry after it: its pronoun and particles ("buksan mo na po yung …")
_AFTER_VERB = r"(?:\s+(?:mo|mong|nyo|niyo|ninyo|natin|nato|ka|kang|kayo|na|po|naman|nga|lang|daw|muna|agad|una|ga)\b)*"
_THE = r"(?:\s+['\u2019]?(?:ang|yung|iyong|ng|the)\b)?"
_CALL_NOUN = r"\s+(?:ang\s+|yung\s+|ng\s+|the\s+)?(?:tawag|call)\b"

# going: "pumunta ka sa", "pakipunta", "mag-punta", "pumaroon ka sa" (go there to), "magtungo ka sa" (text test v80)
_GO = r"\b(?:pumunta|punta|pupunta|magpunta|mag-punta|pakipunta|pumaroon|paroon|magtungo|tumungo)\b"

_ROOMS = {"sala": "living room", "kusina": "kitchen", "banyo": "bathroom", "cr": "bathroom",
          "comfort room": "bathroom", "kwarto": "bedroom", "kuwarto": "bedroom", "pasilyo": "hallway",
          "pintuan sa harap": "front door", "pintuan": "front door", "pinto": "front door", "silid": "bedroom"}
_ROOM = re.compile(r"\b(" + "|".join(sorted(_ROOMS, key=len, reverse=True)) + r")\b", re.IGNORECASE)
_PLACE = r"((?:the\s+)?(?:living room|front door|charging dock|[a-z]+))"

_RULES = rules((
    # (text test v76) an English verb made Tagalog: "pa-on naman ng projector", "i-video call mo si Anna"
    (r"\bpa-?(on|off)\b" + _AFTER_VERB + _THE, r"turn \1 the"), (r"\bpa-?end\b" + _AFTER_VERB + _THE, "end the"),
    (r"\bpaandarin\b" + _AFTER_VERB + _THE, "turn on the"), (r"\bihinto\b", "stop"),
    (r"\b(?:kontakin|i-?facetime)\b" + _AFTER_VERB + r"(?:\s+(?:si|kay))?\b", "video call"),
    (r"\bmag-(drive|go|walk|check|video call|call)\b", r"\1"),
    (r"\bi-(video call|call|charge|text|check|cancel|stop|open|close|end)\b", r"\1"),
    (r"\b(?:mag)?(?:pa)?-?charge\b(?=\s+(?:ka|na|po|ba|muna)\b)|\bmag(?:pa)?-?charge\b", "go charge"),
    # Bisaya words a Cebuano speaker mixes in (text test v78): dayon, unya (then), ug (and)
    (r"\b(?:dayon|unya)\b", "then"), (r"\bug\b(?=\s+(?:i-|paki|punta|tawag|buksan|patayin|go|call|turn))", "and"),
    (r"(^|[.!?,]\s*)una\b", r"\1first"),  # "Una, tawagan mo si Anna, …": first
    # "bago mo tawagan si Clara, …": before you call Clara; "pagdating mo sa …": when you get to the …
    (r"\b(?:bago|before)\s+(?:mo|ka|nyo|niyo)\b", "before you"), (r"\bafter\s+(?:mo|ka|nyo|niyo)\b", "after you"),
    (r"\bpagdating\b" + _AFTER_VERB + r"\s+sa\b", "when you get to the"),
    (r"\bbago\s+['\u2019]?(?:yon|iyon|noon|niyan|yan|non)\b", "before that"),
    (r"\b(?:pumunta|punta|pupunta)\b(?=\s*(?:[,.!?\u2026]|$))", ""),  # the verb said last: "doon ka sa sala pumunta"
    (r"\bpero\s+una\b,?", "but first"), (r"\bpero\b", "but"), (r"\s*,?\s*\bkasi\b", ", because"),
    (r"\b(?:nasaan|saan)\s+(?:ka|kayo)\b", "where are you"), (r"\bkung\b", "if"),
    (r"\bmag-isa\b", "by yourself"), (r"\bngayon\b", "now"),
    (r"\b(?:ayan|ayun)\b[.!,]?", ""),
    # taken back: "…, ay, hindi pala" (no, actually), "wag na lang", "huwag na" (never mind)
    (r"\b(?:ay,?\s+)?hindi\s+pala\b|\b(?:h?uwag|wag)\s+na(?:\s+lang)?\b(?=\s*(?:[,.!?\u2026]|$))", "no, never mind"),
    # "para, para!" (what a jeepney's passenger calls out): stop; elsewhere "para" is "so that"
    (r"(^|[.!?,]\s*)para(?=\s*(?:[!,]|$))", r"\1stop"),
    (r"\s+para\s+(?=(?:ma|mag|maka|makapag|hindi|siya|sila|tayo|ako)\w*)", ", so that "),  # para makita niya …
    # going somewhere: "silipin mo sa front door" (go and look), "lumapit ka dito sa kusina" (come
    # over to), "daan ka sa hallway" (go by), "uwi ka na sa charging dock" (go home to), "diretso ka
    # sa …", "sundan mo ako sa kwarto" (follow me to), "dun ka na lang sa sala" (be in the living room)
    (r"\b(?:silipin|tingnan)\b" + _AFTER_VERB + r"\s+sa\b", "go and check the"),
    (r"\b(?:silipin|tingnan)\b" + _AFTER_VERB, "check"),
    (r"\b(?:halika|halikayo|hali)\b" + _AFTER_VERB + r"(?:\s+(?:dito|rito|rine|dine))?\s+sa\b", "come to the"),
    (r"\b(?:lumapit|lapit)\b" + _AFTER_VERB + r"(?:\s+(?:dito|rito|diyan|dyan))?\s+sa\b", "come to the"),
    (r"\b(?:dumaan|daan)\b" + _AFTER_VERB + r"\s+sa\b", "go by the"),
    (r"\b(?:umuwi|uwi)\b" + _AFTER_VERB + r"\s+sa\b", "go back to the"),
    (r"\b(?:dumiretso|diretso|tumuloy|tuloy)\b" + _AFTER_VERB + r"\s+sa\b", "go straight to the"),
    (r"\bsundan\b" + _AFTER_VERB + r"\s+ako\s+sa\b", "follow me to the"),
    (r"\b(?:d?iyan|dyan|doon|dun)\s+(?:ka|kayo)\b" + _AFTER_VERB + r"\s+sa(?:\s+may)?\b", "go to the"),
    # a room's owner after it: "sa kwarto ni Lola" is the bedroom
    (r"\b(kwarto|kuwarto|bedroom|room|sala)\s+(?:ni|nina)\s+(?:(?:tita|tito|ate|kuya|lola|lolo)\b\s*)?"
     r"(?:(?-i:[A-Z])\w*)?", r"\1"),
    # a call ended: "patayin mo muna ang tawag", "pakipatay na po ng call", "ibaba mo ang tawag"
    (r"\b(?:paki)?(?:patay|patayin|isara|sara|ibaba|baba)\b" + _AFTER_VERB + _CALL_NOUN, "end the call"),
    (r"\bpaki(?:bukas|on)\b" + _AFTER_VERB + _THE, "please turn on the"),
    (r"\b(?:buksan|buksin|i-on)\b" + _AFTER_VERB + _THE, "turn on the"),
    (r"\bpaki(?:patay|sara|off)\b" + _AFTER_VERB + _THE, "please turn off the"),
    (r"\b(?:patayin|isara|i-off)\b" + _AFTER_VERB + _THE, "turn off the"),
    (r"\bpaki(?:tawag|tawagan)\b" + _AFTER_VERB + r"(?:\s+(?:si|kay|ni))?\b", "please call"),
    (r"\b(?:tawagan|tumawag)\b" + _AFTER_VERB + r"(?:\s+(?:si|kay|ni))?\b", "call"),
    (_GO + _AFTER_VERB + r"\s+sa\b", "go to the"), (_GO + _AFTER_VERB, "go to"),
    (r"\bpuntahan\b" + _AFTER_VERB + r"(?:\s+(?:si|kay)\s+\w+)?\s+sa\b", "go to the"),  # "puntahan si Lola sa …"
    (r"\b(?:bumalik|balik)\b" + _AFTER_VERB + r"\s+sa\b", "go back to the"),
    (r"\b(?:bumalik|balik)\b" + _AFTER_VERB, "go back to"),
    (r"\b(?:tumigil|tigil|huminto|hinto)\b(?:\s+(?:ka|kayo))?", "stop"),
    # "dyan ka lang": stay where you are (after "never mind", not a place to go instead)
    (r"\b(?:d?iyan|dyan|doon|dun|dito)\s+(?:ka|kayo)\b", "stay there"),
    # "sa bedroom ka na lang": be in the bedroom instead ("sa hallway ka muna": that first)
    (r"\bsa\s+" + _PLACE + r"\s+(?:ka|kayo)\b", r"go to the \1"),
    (r"\bkaya\b(?:\s+(?:mo|ka|po|naman|na)\b)*\s+ba(?:ng)?\b", "can you"),  # "kaya bang …?": can you …?
    (r"\bmarunong\b(?:\s+(?:mo|ka|po|naman|na)\b)*\s+ba(?:ng)?\b", "do you know how to"),  # knows how: an ability
    # an English verb with Tagalog's pronoun after it: "call mo si Clara", "cancel mo na yung …"
    (r"\b(call|ring|cancel|end|open|close|stop|switch|turn|check|drive|text)\s+(?:mo|nyo|niyo)\b" + _AFTER_VERB,
     r"\1"),
    (r"\b(?:huwag|wag)\b" + _AFTER_VERB + r"(?:\s+(?:munang|muna))", "don't yet"),
    (r"\b(?:huwag|wag)\b" + _AFTER_VERB, "don't"), (r"\bmamaya(?:ng)?\b", "later"),
    (r"\bbukas\s+(?:na\s+lang|natin)\b", "tomorrow"),  # else "bukas" is open
    # "saka ka na pumunta" opening what is said (after a name or "Boss,") is later, not now (text
    # test v78 drove); after a request, "…, at saka ka na mag-charge" is and then
    (r"(^|[.!?]\s*)((?:\w+,\s*)?)saka\s+(?:(?:ka|mo|nyo|kayo)\s+)?na\b", r"\1\2later"),
    (r"\bpagkatapos(?:\s+(?:ay|nun|non|niyan|noon))?\b|\b(?:at\s+)?t?saka\b(?:\s+(?:mo|nyo))?|\btapos\b|\btas\b",
     "then"),
    (r"\b(then|and)\s+sa\b", r"\1 go to the"),  # "tapos sa kusina": then to the kitchen
    (r"\bat\b(?=\s+(?:go|come|check|call|turn|then|end|stop|please|doon|dun|there)\b)", "and"),  # Tagalog "and"
    (r"\s+at\s+nang\b", ", so that"),  # "…, at nang masilip ko …": so that I can look (talk)
    (r"\b(?:doon|dun|roon)\s+(?:mo|nyo|niyo)\b", "then"),  # "…, at doon mo tawagan si Ben": and then, there
    (r"\s+\bo\b(?=\s+\w)", ", or"),  # "…, o kailangan pa kitang turuan?": or
    (r"\bmuna\b", "first"), (r"\bsalamat\b", "thanks"), (r"\bsige\b", "okay"),
    (r"\b(?:si|kay|ni)\s+(?:(?:tita|tito|ate|kuya|lola|lolo)\s+)?(?=(?-i:[A-Z]))", ""),  # before a name
    (r"\b(?:tita|tito|ate|kuya|lola|lolo)\s+(?=(?:Anna|Ben|Clara|Dr|Doctor|Jarvis)\b)", ""),
    (r"(?<!\w)['\u2019]?(?:yung|iyong|ang)\b", "the"),
    (r"\b(?:doon|roon|dun|duon)\b", "there"),  # what is left of "doon" (there), not Scots "doon" (down)
))
_PARTICLES = re.compile(r"\s*\b(?:po|naman|nga|na|lang|daw|pala|ba|mo|ka|diba|agad|ga|ireng|ire|didto|diri|aking"
                        r"|keri)\b",
                        re.IGNORECASE)  # "ga", "ireng" (Batangas), "didto" (Bisaya: there)


# a part still in Tagalog with its own subject ("…, andun siya", "…, tulog na ko": she's there,
# I'm off to sleep) is talk; left in, a word or two after a request reads as one more thing asked
_TALK = re.compile(r"[^,.;!?\u2026]*\b(?:siya|sila|ako|ko|kami|tayo|niya|namin|natin|nila|kita|kitang|nandun|"
                   r"nandoon|andun|andoon|nandito|andito)\b[^,.;!?\u2026]*",
                   re.IGNORECASE)
_ASKS = re.compile(r"\b(?:go|call|turn|end|stop|cancel|please|don't|can you|later|tomorrow|follow me)\b", re.IGNORECASE)


def from_tagalog(text: str) -> str:
    """`text` with the Tagalog of a Taglish request put in English (unchanged without Tagalog)."""
    if not _MARKER.search(text):
        return text
    text = rewrite(text, _RULES)
    text = _PARTICLES.sub("", _TALK.sub(lambda m: m.group(0) if _ASKS.search(m.group(0)) else "", text))
    text = _ROOM.sub(lambda m: _ROOMS[m.group(1).lower()], text)
    return re.sub(r"\bthe the\b", "the", re.sub(r"\bto (?=(?:kitchen|bedroom|bathroom|hallway|living room)\b)",
                                                 "to the ", text), flags=re.IGNORECASE)
