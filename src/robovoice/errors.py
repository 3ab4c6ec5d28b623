"""The one exception tree of robovoice.

Two channels (DESIGN.md §4.6): *robot-side failures* (`RobotFailure` and its
subclasses) are expected at run time and become structured MCP tool errors
the model can act on; everything else (`ConfigError`, `ManifestError`, ...)
is a configuration or programming error and is raised to the caller.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any


class RobovoiceError(Exception):
    """Base of every error robovoice raises on purpose."""


# --- configuration -----------------------------------------------------------------


class ConfigError(RobovoiceError):
    """Bad configuration: a file, a URI, a command-line value. Says what to fix."""


class UnsupportedURIError(ConfigError):
    """A URI (a middleware URI, a robot address) whose scheme is not in its scheme table."""

    def __init__(self, uri: str, supported: list[str], *, what: str = "URI") -> None:
        self.uri = uri
        self.supported = supported
        super().__init__(f"unsupported {what} {uri!r}: supported schemes are {', '.join(supported)}")


class ManifestError(ConfigError):
    """One problem in one manifest file: where it is and how to fix it."""

    def __init__(self, source: str, path: str, message: str, fix: str) -> None:
        self.source = source
        self.path = path
        self.message = message
        self.fix = fix
        super().__init__(f"{source}: at {path}: {message} (fix: {fix})")


class MissingDependencyError(ConfigError):
    """An optional extra is needed for this feature; names the install command."""

    def __init__(self, feature: str, install: str) -> None:
        self.feature = feature
        self.install = install
        super().__init__(f"{feature} needs an optional dependency: {install}")


# --- robot-side failures (become MCP tool errors) ----------------------------------


class RobotFailure(RobovoiceError):
    """A robot-side failure the model can act on: unknown target, node offline, timeout...

    Crosses the middleware as `to_dict()` and comes back to the model as an MCP
    tool result with ``isError: true`` and the body ``{error, message, hint, details}``.
    """

    code = "robot_error"

    def __init__(
        self,
        message: str,
        *,
        code: str | None = None,
        hint: str | None = None,
        details: Mapping[str, Any] | None = None,
    ) -> None:
        super().__init__(message)
        if code is not None:
            self.code = code
        self.message = message
        self.hint = hint
        self.details: dict[str, Any] = dict(details or {})

    def to_dict(self) -> dict[str, Any]:
        return {"error": self.code, "message": self.message, "hint": self.hint, "details": self.details}

    @classmethod
    def from_dict(cls, body: Mapping[str, Any]) -> RobotFailure:
        code = str(body.get("error", cls.code))
        kind = _FAILURE_BY_CODE.get(code, RobotFailure)
        failure = kind.__new__(kind)
        RobotFailure.__init__(
            failure,
            str(body.get("message", code)),
            code=code,
            hint=hint if isinstance(hint := body.get("hint"), str) else None,
            details=details if isinstance(details := body.get("details"), Mapping) else {},
        )
        return failure


class NodeUnavailableError(RobotFailure):
    code = "node_unavailable"


class CallTimeoutError(RobotFailure):
    code = "timeout"


class CancelledByRobotError(RobotFailure):
    code = "cancelled"


class InvalidArgumentsError(RobotFailure):
    code = "invalid_arguments"


_FAILURE_BY_CODE: dict[str, type[RobotFailure]] = {
    c.code: c for c in (NodeUnavailableError, CallTimeoutError, CancelledByRobotError, InvalidArgumentsError)
}


# --- middleware, LLM, audio ----------------------------------------------------------


class MiddlewareError(RobovoiceError):
    """The middleware itself failed (cannot connect, closed)."""


class RobotUnreachableError(RobovoiceError):
    """The robot's MCP server (or its middleware) cannot be reached."""


class LLMError(RobovoiceError):
    """An LLM backend failed: connection, HTTP error, deadline, bad response."""


class BackendUnavailableError(LLMError):
    """Every backend of a chain failed for this turn."""


class AudioError(RobovoiceError):
    """Audio device or format problems."""
