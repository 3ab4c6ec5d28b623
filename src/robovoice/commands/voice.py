"""`robovoice demo` and `robovoice assist`: the voice assistant, scripted or for real use.

    robovoice demo [--output-dir DIR]                     # everything embedded, a scripted conversation
    robovoice assist --robot sim --mic                     # talk to the sim robot through the microphone
    robovoice assist --server http://robot:8765/mcp --input a.wav b.wav --output-dir answers/
    robovoice assist --robot sim --input a.wav --record session.wav   # mic | robot, stereo, checkable

Both print a live transcript: what was heard, tool calls and results, what the robot says,
and per-stage latencies from the user's last word and from the end-of-turn decision.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import time
from pathlib import Path
from typing import Any, TextIO

from robovoice.assistant.connect import RobotConnection, connect_robot
from robovoice.assistant.events import BackendFailed, ToolCalled, ToolReturned
from robovoice.commands.common import (
    add_llm_args,
    add_robot_args,
    backend_from_args,
    config_from_args,
    positive_float,
    robot_config_from_args,
    warm_up,
)
from robovoice.commands.signals import CancelOnSignals
from robovoice.commands.text import one_line as _short
from robovoice.config import RobotConfig
from robovoice.errors import ConfigError

_STAGES = (("transcript", "transcript"), ("first_token", "first token"), ("tool_call", "tool call"),
           ("first_sentence", "first sentence"), ("first_audio", "first audio"))


def register(subparsers: Any) -> None:  # argparse's _SubParsersAction is private
    demo = subparsers.add_parser(
        "demo", help="the voice assistant on the simulated robot, with a scripted conversation",
        description="Everything embedded: the sim robot, its MCP server, the local model and the voice "
                    "pipeline, driven by a conversation synthesised with Piper. Prints a live transcript, "
                    "writes the robot's answers as WAV files, exits 0 only if every step did the right thing.")
    demo.add_argument("--output-dir", type=Path, default=Path("robovoice-demo"), metavar="DIR",
                      help="where the answers (turn-NN.wav) and the whole conversation go (default robovoice-demo)")
    demo.add_argument("--sim-speed", type=positive_float, default=2.0, metavar="X",
                      help="simulated time speed-up, so drives take seconds (default 2)")
    demo.add_argument("--console", nargs="?", type=int, const=8780, metavar="PORT",
                      help="watch it in the robot console: serve the page on 127.0.0.1:PORT (default 8780)")
    add_llm_args(demo)
    demo.set_defaults(run=run_demo_command)

    assist = subparsers.add_parser(
        "assist", help="the voice assistant for real use: microphone and speaker, or WAV files",
        description="Wake word -> VAD -> speech-to-text (or audio to an audio-capable model) -> tools -> "
                    "speech. With --input each file is spoken into a simulated room, one after another, "
                    "in one conversation.")
    add_robot_args(assist, default_speed=1.0)
    add_llm_args(assist)
    source = assist.add_mutually_exclusive_group(required=True)
    source.add_argument("--mic", action="store_true", help="listen on the default microphone (needs PortAudio)")
    source.add_argument("--input", nargs="+", type=Path, metavar="FILE.wav", help="WAV files to process")
    assist.add_argument("--output-dir", type=Path, metavar="DIR", help="write the spoken answers here")
    assist.add_argument("--record", type=Path, metavar="OUT.wav",
                        help="with --input: write the session as a stereo WAV aligned sample by sample with the "
                             "first input file: channel 1 what the microphone heard, channel 2 what the robot "
                             "played (voice.recording)")
    assist.add_argument("--stt", choices=["whisper", "moonshine", "none"], default=None,
                        help="speech-to-text model (default: [voice] stt of the config, whisper; "
                             "none: only with an audio-capable --llm)")
    assist.set_defaults(run=run_assist_command)


# --- the live transcript --------------------------------------------------------------------------


def _args(arguments: dict[str, Any]) -> str:
    return ", ".join(f"{k}={json.dumps(v, ensure_ascii=False)}" for k, v in arguments.items())


def latency_line(marks: dict[str, float]) -> str:
    parts = []
    for key, label in _STAGES:
        value = marks.get(key)
        if value is None and key == "tool_call":
            value = min((v for k, v in marks.items() if k.startswith("tool_call:")), default=None)
        if value is not None:
            parts.append(f"{label} {value:.0f}")
    return " · ".join(parts) + " ms" if parts else ""


class TranscriptPrinter:
    """Prints pipeline events (voice and assistant), one line each, with the elapsed time."""

    def __init__(self, out: TextIO = sys.stdout) -> None:
        self.out = out
        self.start = time.perf_counter()

    def line(self, text: str) -> None:
        print(f"[{time.perf_counter() - self.start:6.1f}s] {text}", file=self.out, flush=True)

    def __call__(self, event: Any) -> None:
        from robovoice.voice import events as v

        match event:
            case v.WakeWordHeard(score=score, during_playback=during, sure=sure):
                unsure = "" if sure else ", unsure: it counts if the words name the robot"
                self.line(f"  · wake word ({score:.2f}{unsure}){' while the robot spoke' if during else ''}")
            case v.WakeWordRejected():
                self.line("  · wake phrase in the robot's own playback: ignored")
            case v.TranscriptReady(text=text, inference_ms=ms):
                self.line(f"  heard: \"{_short(text)}\" (speech-to-text {ms:.0f} ms)")
            case v.VoiceTurnStarted(mode="audio", audio_s=seconds):
                self.line(f"  heard: {seconds:.1f} s of audio, sent to the model as it is")
            case v.UtteranceIgnored(reason=reason, text=text):
                said = f" (\"{_short(text)}\")" if text else ""
                self.line(f"  · speech ignored: {reason.replace('_', ' ')}{said}")
            case ToolCalled(name=name, arguments=arguments):
                self.line(f"  → {name}({_args(arguments)})")
            case ToolReturned(name=name, text=text, is_error=error, duration_ms=ms):
                self.line(f"  ← {name}{' ERROR' if error else ''}: {_short(text, 90)} ({ms:.0f} ms)")
            case BackendFailed(reason=reason):
                self.line(f"  ! no language model answered: {_short(reason, 90)}")
            case v.SentenceSpoken(text=text, kind=kind):
                self.line(f"  robot{'' if kind == 'reply' else f' ({kind})'}: \"{_short(text)}\"")
            case v.BargedIn():
                self.line("  ! barge-in: the robot stops talking and listens")
            case v.StopHeard(text=text, tool=tool):
                how = f"{tool}, straight, no model" if tool else "the robot declares no stop tool"
                self.line(f"  ! STOP (\"{_short(text)}\"): {how}")
            case v.RobotStopped(ok=ok, latency_ms=ms, detail=detail, from_last_word_ms=word_ms):
                after = f"{word_ms:.0f} ms after the last word" if word_ms is not None else \
                    f"{ms:.0f} ms after the end of turn"
                self.line(f"  ■ robot {'stopped' if ok else 'DID NOT STOP'} {after}" + ("" if ok else f": {detail}"))
            case v.VoiceTurnFinished(cancelled=cancelled, latency_ms=marks, result=result):
                line = latency_line(dict(marks))
                spoken = latency_line(result.metrics.from_speech_end()) if result is not None else ""
                if cancelled:
                    self.line("  · turn cancelled")
                elif spoken:  # "end of speech": the user's last word (issue 12)
                    self.line(f"  latency from end of speech: {spoken}")
                    self.line(f"  latency from the end-of-turn decision: {line}")
                elif line:
                    self.line(f"  latency from the end-of-turn decision: {line}")
            case _:
                pass


# --- demo ---------------------------------------------------------------------------------------------


def run_demo_command(args: argparse.Namespace) -> int:
    return asyncio.run(_demo(args))


async def _demo(args: argparse.Namespace) -> int:
    from robovoice.assistant.metrics import summarise
    from robovoice.voice.demo import StepChecked, StepStarted, run_demo
    from robovoice.voice.models import load_voice_models

    printer = TranscriptPrinter()
    printer.line("loading the voice models, the robot and the language model ...")
    config = config_from_args(args)
    backend = backend_from_args(args, config)
    models = await asyncio.to_thread(load_voice_models, wake_model=config.voice.wake_model, stt=config.voice.stt,
                                         wake_phases=config.voice.wake_phases)

    def on_step(event: StepStarted | StepChecked) -> None:
        step = event.step
        if isinstance(event, StepStarted):
            print(file=printer.out)
            printer.line(f"── {event.index}. {step.title} ──")
            if step.remote:
                printer.line(f"  remote caller (through the robot's speaker): \"{step.remote}\"")
            if step.say:
                printer.line(f"  you: \"{step.say}\"")
            if step.stop:
                printer.line(f"  you, once it drives: \"{step.stop}\"")
        else:
            printer.line(f"  {'✔ ok' if event.ok else '✘ FAILED: ' + str(event.problem)}")

    try:
        async with connect_robot(RobotConfig(address=f"sim://?speed={args.sim_speed:g}")) as link:
            if link.sim is None:
                raise ConfigError("the demo needs the embedded sim robot")
            await warm_up(backend, await link.tools.specs())
            printer.line(f"ready: model {backend.name}, sim robot at {args.sim_speed:g}x; the conversation starts")
            from robovoice.console.beside import console_beside

            async with console_beside(link.tools, backend, port=args.console, say=printer.line) as watched:
                report = await run_demo(models, backend, link.tools, link.sim, output_dir=args.output_dir,
                                        observer=watched(printer), on_step=on_step, config=config.voice)
    finally:
        await backend.aclose()

    out = printer.out
    print("\n" + "=" * 96, file=out)
    print(f"{'step':<40} {'result':<8} {'tool calls':<34} {'first audio':>11}", file=out)
    print("-" * 96, file=out)
    for s in report.steps:
        first = s.latency_ms.get("first_audio")
        stop = s.latency_ms.get("stop")
        latency = f"{first:.0f} ms" if first is not None else (f"stop {stop:.0f} ms" if stop is not None else "-")
        calls = _short(", ".join(s.calls) or "-", 34)
        print(f"{s.index}. {s.step.title:<37} {'ok' if s.ok else 'FAILED':<8} {calls:<34} {latency:>11}", file=out)
    print("-" * 96, file=out)
    stages = summarise(report.turns)
    for stage, figures in stages.items():
        if stage in ("finished",) or stage.endswith("_ms"):
            continue
        print(f"  {stage:<16} p50 {figures['p50']:>7.0f} ms   p95 {figures['p95']:>7.0f} ms   (n={figures['n']})",
              file=out)
    passed = sum(s.ok for s in report.steps)
    print(f"{passed}/{len(report.steps)} steps did the right thing in {report.wall_s:.0f} s; "
          f"{len(report.files)} WAV files in {args.output_dir}/", file=out)
    return 0 if report.ok else 1


# --- assist -------------------------------------------------------------------------------------------


def run_assist_command(args: argparse.Namespace) -> int:
    return asyncio.run(_assist(args))


async def _assist(args: argparse.Namespace) -> int:
    from robovoice.voice.models import load_voice_models

    printer = TranscriptPrinter()
    config = config_from_args(args)
    backend = backend_from_args(args, config)
    stt = args.stt or config.voice.stt
    if stt == "none" and not backend.accepts_audio:
        raise ConfigError("--stt none needs an audio-capable model (--llm URL --audio-input)")
    if args.input:
        missing = [str(p) for p in args.input if not p.is_file()]
        if missing:
            raise ConfigError(f"no such WAV file: {', '.join(missing)}")
    if args.record is not None:
        if not args.input:
            raise ConfigError("--record needs --input: it records the simulated room the WAV files are spoken into")
        if not args.record.parent.is_dir():
            raise ConfigError(f"--record {args.record}: no folder {args.record.parent}; create it first")
    target = robot_config_from_args(args, config)
    printer.line("loading the voice models ...")
    models = await asyncio.to_thread(load_voice_models, wake_model=config.voice.wake_model, stt=stt,
                                         wake_phases=config.voice.wake_phases)
    try:
        async with connect_robot(target) as link:
            await warm_up(backend, await link.tools.specs())
            printer.line(f"ready: robot {target.address}, model {backend.name}")
            if args.input:
                await _assist_files(args, models, backend, link, printer, config)
            else:
                await _assist_mic(args, models, backend, link, printer, config)
    finally:
        await backend.aclose()
    return 0


def _pipeline_options(link: RobotConnection, config: Any) -> dict[str, Any]:
    from robovoice.voice.config import PipelineConfig

    options: dict[str, Any] = {"config": PipelineConfig.from_config(config.voice)}
    if link.sim is not None:
        sim = link.sim
        options["moving"] = lambda: sim.state.moving
    return options


async def _assist_files(args: argparse.Namespace, models: Any, backend: Any, link: RobotConnection,
                        printer: TranscriptPrinter, config: Any) -> None:
    from robovoice.audio.wav import read_wav
    from robovoice.voice.pipeline import VoicePipeline
    from robovoice.voice.room import SimulatedRoom

    room = SimulatedRoom(record=args.record is not None)  # paced in real time, like a microphone
    pipeline = VoicePipeline(models, backend, link.tools, source=room.mic, sink=room.speaker,
                             reference=room.reference, observer=printer, output_dir=args.output_dir,
                             **_pipeline_options(link, config))
    starts: list[float] = []  # stream time at which each input file starts

    async def feed() -> None:
        try:
            for path in args.input:
                printer.line(f"── {path} ──")
                speech = room.say(read_wav(path), gap_s=0.5)
                starts.append(speech.start)
                await speech.finished(timeout=600)
                await room.until(room.now + 0.8)
                await pipeline.wait_idle(timeout=300)
        finally:
            room.close()

    async with asyncio.TaskGroup() as group:
        group.create_task(pipeline.run(finish_timeout_s=60.0), name="assist-pipeline")
        group.create_task(feed(), name="assist-files")
    if args.output_dir:
        printer.line(f"answers written to {args.output_dir}/")
    if args.record is not None and starts:
        from robovoice.voice.recording import write_session

        write_session(args.record, room, origin=starts[0])
        offsets = ", ".join(f"{p.name} at {t - starts[0]:.3f} s" for p, t in zip(args.input, starts, strict=False))
        printer.line(f"session recorded to {args.record} (channel 1 microphone, channel 2 robot; {offsets})")


async def _assist_mic(args: argparse.Namespace, models: Any, backend: Any, link: RobotConnection,
                      printer: TranscriptPrinter, config: Any) -> None:
    from robovoice.audio.devices import MicrophoneSource, SpeakerSink
    from robovoice.audio.format import MODEL_FORMAT, PIPER_FORMAT
    from robovoice.audio.streams import AudioSource
    from robovoice.voice.device import DeviceReaction, GuardedSource
    from robovoice.voice.echo import PlaybackReference
    from robovoice.voice.pipeline import VoicePipeline
    from robovoice.voice.playback import ReferencedSink

    reference = PlaybackReference()
    # opened now, so that a machine with no microphone at all is told at once; a microphone that
    # fails, stalls or is unplugged later is reopened by the guard (the robot stopped meanwhile)
    first: list[AudioSource] = [MicrophoneSource(MODEL_FORMAT)]
    mic = GuardedSource(lambda: first.pop() if first else MicrophoneSource(MODEL_FORMAT))
    speaker = ReferencedSink(SpeakerSink(PIPER_FORMAT), reference)
    options = _pipeline_options(link, config)
    if link.sim is not None:  # the sim's call has no audio: its remote voice counts as playback
        sim = link.sim
        options["remote_speaking"] = lambda: sim.state.remote_speaking
    pipeline = VoicePipeline(models, backend, link.tools, source=mic, sink=speaker, reference=reference,
                             observer=printer, output_dir=args.output_dir, sink_format=PIPER_FORMAT, **options)
    mic.on_event = DeviceReaction(pipeline)
    printer.line("listening: say \"Hey Jarvis, ...\" (Ctrl-C to end)")
    with CancelOnSignals() as stop:
        try:
            await pipeline.run(finish_timeout_s=10.0)
        finally:
            await mic.aclose()
            await speaker.aclose()
    if mic.failure:
        printer.line(mic.failure)
    if stop.signalled:
        printer.line("stopped")
