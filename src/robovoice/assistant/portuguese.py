"""Portuguese said inside English, as Brazilian and Portuguese grandparents, their children and
their carers say it: requests, order words, time words, courtesy and rooms put in English, for the
reading only (text test v104: "Liga pra Anna, please" and "Desliga o projector, filho" were talk,
"vai pro quarto" and "Primeiro the bathroom" were not heard as steps).

"Liga" is both "call" and "switch on": before "pra", "pro" or "para" a person follows (call), before
"o" or "a" a thing (switch on). Nothing is rewritten unless a word only Portuguese has was said
(`_MARKER`): "sala", "porta" and "pro" alone are not taken from English.
"""

from __future__ import annotations

import re

from robovoice.assistant.dialects import rewrite_where, rules

_TO = r"(?:pro|pra|pros|pras|para o|para a|para|ao|à|a)"
_MARKER = re.compile(r"\b(?:vai|vá|vem|venha|volta|liga|ligar|desliga|desligar|acende|primeiro|depois|obrigad[oa]"
                     r"|brigad[oa]|agora|né|tá(?: bom)?|ta bom|olha|não"
                     r"|nao(?= (?:liga|ligue|vai|vá|va|desliga|precisa))|amanh[aã]|ainda|cozinha|banheiro|quarto"
                     r"|corredor|projetor|carregador|filh[oa]|querid[oa]|netinh[oa]|net[oa]|vizinh[oa]|nossa"
                     r"|por favorzinho|rapidinho|j[aá] j[aá])\b", re.IGNORECASE)

_RULES = rules((
    # what is not wanted, before the requests below: "não liga pra Ben", "ainda não", "não precisa"
    (r"\bainda n[aã]o\b", "not yet"), (r"\bn[aã]o precisa(?: de)?\b", "no need to"),
    (r"\bn[aã]o (?:liga|ligue) " + _TO + r"\b", "don't call"),
    (r"\bn[aã]o (?:vai|vá|va)\s+" + _TO + r"\s+(?=\w)", "don't go to the "),
    (r"\bn[aã]o (?:vai|vá|va)\b", "don't go"),
    (r"\bn[aã]o (?:desliga|desligue)\b", "don't turn off"), (r"\bn[aã]o (?:liga|ligue|acende)\b", "don't turn on"),
    (r"\bnão\b", "no"),  # (not "nao" alone: a Japanese name)
    # requests: call, switch on and off, go, come, come back
    (r"\b(?:liga|ligue|ligar|liga lá)\s+" + _TO + r"\s+(?:o |a )?(?=\w)", "call "),
    (r"\b(?:desliga|desligue|desligar)\s+(?:o|a)\b", "turn off the"),
    (r"\b(?:desliga|desligue|desligar)\b", "turn off"),
    (r"\b(?:liga|ligue|acende|acenda)\s+(?:o|a)\b", "turn on the"), (r"\b(?:liga|ligue|acende|acenda)\b", "turn on"),
    (r"\b(?:vai|vá|va|ir)\s+(?:lá\s+)?" + _TO + r"\s+(?=\w)", "go to the "),
    (r"\b(?:vem|venha)\s+(?:c[aá]|aqui)\b", "come here"), (r"\b(?:vem|venha)\s+" + _TO + r"\s+(?=\w)", "come to the "),
    (r"\b(?:volta|volte)\s+" + _TO + r"\s+(?=\w)", "go back to the "), (r"\b(?:vai|vá) carregar\b", "go charge"),
    (r"\bvai lá\b|\bvai\b(?=\s*[,.!?]|$)", "go"),
    # order and time words
    (r"\bprimeiro\b", "first"), (r"\bdepois disso\b", "after that"), (r"\bantes disso\b", "before that"),
    (r"\be depois\b", "and then"), (r"\bdepois\b", "then"), (r"\bagora\b", "now"), (r"\bmais tarde\b", "later"),
    (r"\bamanh[aã]\b", "tomorrow"), (r"\bainda\b", "yet"), (r"\bj[aá] j[aá]\b|\brapidinho\b", "quickly"),
    # courtesy, openers and tags, which ask nothing; whom it is for
    (r"\bpor favor(?:zinho)?\b", "please"), (r"\b(?:muito )?(?:obrigad[oa]|brigad[oa])\b", "thank you"),
    (r"^(?:(?:olha|nossa|gente|ai|ué|então|bom)\b[\s,!.\u2026]*)+", ""),
    (r"\s*,?\s*\b(?:n[ée]|t[aá] bom|t[aá])\b(?=\s*(?:[,.!?\u2026]|$))", ""),
    (r"\bminha filha\b", "my daughter"), (r"\bmeu filho\b", "my son"), (r"\b(?:a |o )?vizinh[oa]\b", "the neighbour"),
    (r"\b(?:o |a )?m[eé]dico\b|\b(?:o |a )?doutor[a]?\b", "the doctor"),
    (r"\b(?:filh[oa]|querid[oa]|meu bem)\b", "dear"),
    # rooms, with a Portuguese article before them said in English
    (r"\b(?:a |o )?(?:porta da frente|porta de entrada)\b", "the front door"),
    (r"\b(?:a |o )?cozinha\b", "the kitchen"), (r"\b(?:o )?banheiro\b|\b(?:a )?casa de banho\b", "the bathroom"),
    (r"\b(?:o )?quarto\b", "the bedroom"), (r"\b(?:a )?sala(?: de estar)?\b", "the living room"),
    (r"\b(?:o )?corredor\b", "the hallway"), (r"\b(?:o )?carregador\b", "the charging dock"),
    (r"\b(?:o )?projetor\b", "the projector"), (r"\bthe the\b", "the"),
))


def from_portuguese(text: str) -> str:
    """`text` with its Portuguese put in English; unchanged where no word only Portuguese has was said."""
    return rewrite_where(_MARKER, text, _RULES)
