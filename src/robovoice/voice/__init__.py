"""The voice pipeline: wake word -> VAD -> (speech-to-text) -> assistant -> speech, with
turn-taking, barge-in, self-voice rejection and a local spoken stop (docs/voice.md).

Modules, in data-flow order:

- `echo`: the playback reference and the echo canceller (self-voice rejection, part 1);
- `frontend`: echo cancellation + wake word + VAD per 80 ms frame, with verdicts on what
  was heard during playback (part 2);
- `turns`: turn-taking (listening / woken / in-turn / speaking / follow-up), pure logic;
- `stop`: the local stop phrases; `motion`: is the robot moving?;
- `speech`: sentence-by-sentence speech output, synthesis overlapping playback, barge-in;
- `progress`: short spoken progress of long actions;
- `inference`: per-model executors, the one bridge from blocking models to asyncio;
- `pipeline`: all of it together; `models`: loading the real models;
- `room`: a simulated room (microphone, speaker, echo) for headless runs;
- `evaluation`: audio cases for `robovoice eval`; `demo`: the scripted demo; `bench`: benchmarks.

Needs the ``robovoice[voice]`` extra; nothing heavy is imported here.
"""
