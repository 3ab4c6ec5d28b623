"""The voice side of robovoice: audio values and I/O, wake word, VAD, STT, TTS.

Modules, in data-flow order (each seam is a `typing.Protocol` with a real implementation
and a fake):

- `format`: `AudioFormat`, `AudioChunk` and every conversion (int16/float32, channels,
  resampling, framing) -- the only place audio changes format.
- `streams`: the `AudioSource` / `AudioSink` seams; `wav` (files, memory) and `devices`
  (microphone, speaker over sounddevice) implement them.
- `wake`: `WakeWordDetector` (openWakeWord), the pure `WakeDecider`, `WakeDetected` events.
- `vad`: `VADModel` (Silero), the pure `Endpointer`, `SpeechStarted` / `SpeechEnded` events.
- `stt`: `Transcriber` (Moonshine, optional Whisper) -> `Transcript`.
- `sentences`: streaming `SentenceSplitter` for LLM text -> TTS (pure Python, no numpy).
- `tts`: `Synthesizer` (Piper).
- `fakes`: model-free stand-ins for the model seams.
- `bench`: measurements of the above.

Nothing heavy is imported here; everything except `sentences` needs numpy (the
``robovoice[voice]`` extra), and models are loaded only when their class is constructed.
"""
