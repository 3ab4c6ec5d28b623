"""The voice pipeline: wake word -> VAD -> (speech-to-text) -> assistant -> speech, with
turn-taking, barge-in, self-voice rejection and a local spoken stop (docs/voice.md).

Modules, in data-flow order:

- `echo`: the playback reference and the echo canceller (self-voice rejection, part 1);
- `listener`: echo cancellation + wake word + VAD per 80 ms frame, with verdicts on what
  was heard during playback (part 2);
- `router`: what was heard becomes a command turn, a stop check, or nothing (never waiting);
- `turns`: turn-taking (listening / woken / in-turn / speaking / follow-up), pure logic;
- `command`: one command turn, utterance -> assistant -> speech, with its own observer;
- `stopping`, `stop`: the spoken stop and its phrases; `motion`: is the robot moving?;
- `roles`: the robot's stop / motion / pose tools and phrases, from its manifests;
- `speech`: sentence-by-sentence speech output, synthesis overlapping playback, barge-in;
- `progress`: what is said while a tool runs; `answers`: results and recorded answers;
- `floor`: who holds the floor (the active turn, stop checks); `inference`: per-model
  executors, the one bridge from blocking models to asyncio;
- `pipeline`: all of it assembled; `config`: its settings from ``[voice]``; `models`: loading
  the real models;
- `room`: a simulated room (microphone, speaker, echo) for headless runs;
- `evaluation`: audio cases for `robovoice eval`; `demo`: the scripted demo; `bench`: benchmarks.

Needs the ``robovoice[voice]`` extra; nothing heavy is imported here.
"""
