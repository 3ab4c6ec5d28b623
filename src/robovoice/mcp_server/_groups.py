"""Task groups around a ``yield``, without turning the caller's own errors into groups.

`asyncio.TaskGroup` (and anyio's, inside the SDK client) wrap an exception raised in their
body in an `ExceptionGroup`. A context manager that owns background tasks while it yields
would then hand its caller a group for the caller's *own* error (a `ConfigError` raised
inside ``async with open_robot_side(...)`` would surface as ``ExceptionGroup``). `owned_tasks`
and `unwrapped` re-raise a lone exception (however deeply nested) as itself; several
at once stay a group.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager


def sole_error(group: BaseExceptionGroup[BaseException]) -> BaseException | None:
    """The one exception inside (nested) single-member groups, or None when there are several."""
    error: BaseException = group
    while isinstance(error, BaseExceptionGroup):
        if len(error.exceptions) != 1:
            return None
        error = error.exceptions[0]
    return error


@asynccontextmanager
async def unwrapped() -> AsyncIterator[None]:
    """Re-raise a lone exception out of task-group wrapping as itself."""
    error: BaseException | None = None
    try:
        yield
    except BaseExceptionGroup as caught:
        error = sole_error(caught)
        if error is None:
            raise
    if error is not None:
        raise error


@asynccontextmanager
async def owned_tasks() -> AsyncIterator[asyncio.TaskGroup]:
    """An `asyncio.TaskGroup` whose body's own exception comes out unwrapped."""
    async with unwrapped(), asyncio.TaskGroup() as group:
        yield group
