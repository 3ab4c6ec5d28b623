from robovoice.llm.base import ChatMessage, ToolCall
from robovoice.llm.local import COMPOUND_CALLS, call_budget


def test_single_requests_get_one_call_per_step() -> None:
    assert call_budget([ChatMessage("system", "s"), ChatMessage("user", "Drive to the kitchen.")], 1) == 1
    assert call_budget([ChatMessage("user", "Andrew's room")], 1) == 1  # words, not substrings


def test_compound_requests_share_a_budget_across_steps() -> None:
    asked = [ChatMessage("user", "Go to the living room and turn on the projector.")]
    assert call_budget(asked, 1) == COMPOUND_CALLS
    after_one = [*asked, ChatMessage("assistant", "", (ToolCall("c1", "navigate_to", "{}"),)),
                 ChatMessage("tool", "{}", tool_call_id="c1")]
    assert call_budget(after_one, 1) == COMPOUND_CALLS - 1
    after_three = [*after_one, ChatMessage("assistant", "", (ToolCall("c2", "a", "{}"), ToolCall("c3", "b", "{}")))]
    assert call_budget(after_three, 1) == 1  # never zero: the step bound of the loop ends the turn
    # An earlier compound request does not widen a later single one.
    assert call_budget([*after_three, ChatMessage("user", "What time is it?")], 1) == 1
