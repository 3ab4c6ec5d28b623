"""`python -m robovoice.eval.patient`: the embedded model built by the command line gets
deadlines no loaded machine reaches, so an accuracy run never counts a slow model as dead."""

from __future__ import annotations

import pytest

from robovoice.eval import patient
from robovoice.llm import registry
from robovoice.llm.base import LOCAL_DEADLINES
from robovoice.llm.local import LocalLlamaBackend


def test_the_embedded_model_gets_the_patient_deadlines(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(registry, "LOCAL_DEADLINES", LOCAL_DEADLINES)  # put back after the test
    assert registry.backend_from_spec("local").deadlines == LOCAL_DEADLINES  # type: ignore[attr-defined]
    with pytest.raises(SystemExit) as done:
        patient.main(["eval", "--help"])
    assert done.value.code == 0
    local = registry.backend_from_spec("local")
    assert isinstance(local, LocalLlamaBackend) and local.deadlines == patient.PATIENT_DEADLINES
    assert local.deadlines.first_token_s >= 10 * LOCAL_DEADLINES.first_token_s
    # a URL backend keeps its own kind's deadlines
    assert registry.backend_from_spec("http://127.0.0.1:9/v1#m").deadlines != patient.PATIENT_DEADLINES  # type: ignore[attr-defined]
