"""The LLM seam and its backends: OpenAI-compatible HTTP, embedded llama.cpp, failover.

Light to import: llama-cpp-python is imported only when a local model loads, and
the fake server (starlette/uvicorn) lives in `robovoice.llm.fake_server`.
"""

from robovoice.llm.base import (
    AudioPart,
    ChatMessage,
    ContentPart,
    DeadlineExceededError,
    Deadlines,
    Finished,
    LLMBackend,
    LLMEvent,
    LLMHTTPError,
    TextDelta,
    TextPart,
    ToolCall,
    ToolCallRequested,
    ToolSpec,
    Usage,
)
from robovoice.llm.failover import (
    FALLBACK_MESSAGE,
    AllBackendsFailedError,
    BackendHealth,
    Backoff,
    FailoverBackend,
)
from robovoice.llm.local import LocalLlamaBackend
from robovoice.llm.openai_compat import OpenAICompatBackend
from robovoice.llm.registry import BackendSpec, api_key_from, backend_from_spec, chain_from_specs

__all__ = [
    "FALLBACK_MESSAGE",
    "AllBackendsFailedError",
    "AudioPart",
    "BackendHealth",
    "BackendSpec",
    "Backoff",
    "ChatMessage",
    "ContentPart",
    "DeadlineExceededError",
    "Deadlines",
    "FailoverBackend",
    "Finished",
    "LLMBackend",
    "LLMEvent",
    "LLMHTTPError",
    "LocalLlamaBackend",
    "OpenAICompatBackend",
    "TextDelta",
    "TextPart",
    "ToolCall",
    "ToolCallRequested",
    "ToolSpec",
    "Usage",
    "api_key_from",
    "backend_from_spec",
    "chain_from_specs",
]
