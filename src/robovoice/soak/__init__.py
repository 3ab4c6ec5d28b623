"""The soak benchmark (`robovoice bench soak`, issue 14): the whole embedded assistant
listening to hours of a home in accelerated stream time, with its process watched.

    report = await run_soak(models, backend, SoakSettings(hours=2))
    write_memory_plot(report, Path("docs/soak-memory.png"))
"""

from __future__ import annotations

from pathlib import Path

from robovoice.soak.plot import write_png_plot
from robovoice.soak.report import SoakReport
from robovoice.soak.runner import SoakSettings, run_soak

__all__ = ["SoakReport", "SoakSettings", "run_soak", "write_memory_plot"]


def write_memory_plot(report: SoakReport, path: Path) -> Path:
    """RSS (all, and anonymous only), Python heap blocks and gc-tracked objects over simulated minutes, as a PNG."""
    xs = [s.sim_s / 60.0 for s in report.samples]
    return write_png_plot(path, [("PROCESS RSS (MIB)", xs, [s.rss_mib for s in report.samples]),
                                 ("RSS WITHOUT FILE PAGES (ANON, MIB)", xs, [s.rss_anon_mib for s in report.samples]),
                                 ("PYTHON HEAP BLOCKS (THOUSANDS)", xs, [s.heap_blocks / 1000 for s in report.samples]),
                                 ("GC OBJECTS (THOUSANDS)", xs, [s.gc_objects / 1000 for s in report.samples])],
                          x_label="SIMULATED MINUTES")
