"""A hosted node's JSON reply over ROS 2 (`robovoice_msgs`): malformed ones become a structured
`internal_error`, never an exception the MCP server does not expect."""

from __future__ import annotations

import pytest

from robovoice.errors import RobotFailure
from robovoice.middleware.ros2_calls import _json_outcome


def test_replies_values_failures_and_garbage() -> None:
    assert _json_outcome('{"arrived": "kitchen"}', "") == {"arrived": "kitchen"}
    assert _json_outcome("", "") is None
    with pytest.raises(RobotFailure) as busy:
        _json_outcome("", '{"error": "busy", "message": "in a call with Anna"}')
    assert busy.value.code == "busy" and busy.value.message == "in a call with Anna"
    for result, error in (("", "not json"), ("", "[1, 2]"), ("{broken", "")):
        with pytest.raises(RobotFailure) as bad:
            _json_outcome(result, error)
        assert bad.value.code == "internal_error" and "malformed reply" in bad.value.message
