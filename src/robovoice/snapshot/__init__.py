"""Latest-value buffers with staleness (the snapshot node)."""

from __future__ import annotations

from robovoice.snapshot.store import (
    Snapshot,
    SnapshotImage,
    SnapshotStore,
    UntrackedTopicError,
    as_image,
)

__all__ = ["Snapshot", "SnapshotImage", "SnapshotStore", "UntrackedTopicError", "as_image"]
