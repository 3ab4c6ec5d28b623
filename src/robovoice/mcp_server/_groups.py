"""Task groups around a ``yield``, without turning the caller's own errors into groups.

`asyncio.TaskGroup` wraps an exception raised in its body in an `ExceptionGroup`. A
context manager that owns background tasks in a group while it yields would then hand its
caller a group for the caller's *own* error (a `ConfigError` raised inside
``async with open_robot(...)`` would surface as ``ExceptionGroup``). `owned_tasks` re-raises
a lone exception as itself; several at once stay a group.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager


@asynccontextmanager
async def owned_tasks() -> AsyncIterator[asyncio.TaskGroup]:
    error: BaseException | None = None
    try:
        async with asyncio.TaskGroup() as group:
            yield group
    except BaseExceptionGroup as caught:
        if len(caught.exceptions) != 1:
            raise
        error = caught.exceptions[0]
    if error is not None:
        raise error
