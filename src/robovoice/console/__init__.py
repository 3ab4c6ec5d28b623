"""The robot console: one page and a small API to watch the robot, the conversation and every
tool call live, talk to the robot through the browser's microphone, and call tools by hand.

- `hub`: conversation events as JSON, grouped into turns, fanned out to WebSocket listeners;
- `watch`: the robot's state, read through its own MCP tools and snapshots several times a second;
- `service`: the console's work (typed turns, tools by hand, its audit log, the voice pipeline);
- `voice`: the browser's microphone and speaker as the voice pipeline's source and sink;
- `app`: the HTTP routes and WebSockets behind the MCP HTTP server's guard (docs/console.md).
"""
