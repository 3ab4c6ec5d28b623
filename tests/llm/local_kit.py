"""What the tests of the embedded model share: a prompt and deadlines for a busy machine."""

from __future__ import annotations

from robovoice.llm.base import ChatMessage, Deadlines

# Correctness, not speed, is tested: deadlines for a machine shared with other work.
PATIENT = Deadlines(first_token_s=300, idle_s=60, total_s=600)
SYSTEM = ChatMessage("system", "You are the voice assistant of a home robot. Answer briefly. Use the functions to act.")
