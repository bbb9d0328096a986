"""The renderers `compare_mitsuba.py` times: Mitsuba 3 variants in this process, and mcrt's
`render` example as a child process. Each contender loads a scene (`setup`), warms up, and
renders one image per call with its own timing (`render` -> `Sample`)."""

from __future__ import annotations

import glob
import os
import re
import resource
import shlex
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
WARMUP_SEED = 1_000_003


def fail(msg: str) -> None:
    """Print an error and exit with status 2."""
    print(f"compare_mitsuba: error: {msg}", file=sys.stderr)
    sys.exit(2)


# ---------------------------------------------------------------- Mitsuba


def find_libllvm() -> str | None:
    """Locate a libLLVM (16 or newer) for Dr.Jit's LLVM backend, if one is installed."""
    patterns = [
        "/usr/lib/x86_64-linux-gnu/libLLVM.so.*",
        "/usr/lib/x86_64-linux-gnu/libLLVM-*.so",
        "/usr/lib/aarch64-linux-gnu/libLLVM.so.*",
        "/usr/lib/llvm-*/lib/libLLVM*.so*",
    ]
    for pattern in patterns:
        for path in sorted(glob.glob(pattern), reverse=True):
            m = re.search(r"LLVM[.-](?:so\.)?(\d+)", os.path.basename(path))
            if m and int(m.group(1)) >= 16:
                return path
    return None


def import_mitsuba(variants: list[str]):
    """Import mitsuba (and numpy), with a clear message if they are missing."""
    if "llvm_ad_rgb" in variants and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib
    try:
        import drjit as dr
        import mitsuba as mi
        import numpy as np  # noqa: F401  (needed by mi.Bitmap -> array)
    except ImportError as e:
        fail(
            f"cannot import {e.name}: install the requirements with "
            "'pip install -r scripts/requirements.txt' (see scripts/README.md); "
            "mitsuba is needed even with --skip-mitsuba, to read the EXR images"
        )
    missing = [v for v in variants if v not in mi.variants()]
    if missing:
        fail(f"this mitsuba build lacks the variant(s) {missing}")
    return mi, dr


def check_variant(mi, variant: str) -> None:
    """Select a Mitsuba variant; explain the libLLVM requirement if it fails."""
    try:
        mi.set_variant(variant)
        if variant.startswith("llvm"):
            mi.Float(1.0) + 1.0  # forces the LLVM backend to initialise
    except Exception as e:  # noqa: BLE001 (drjit raises several types)
        hint = ""
        if variant.startswith("llvm"):
            hint = (
                " -- the LLVM variants need libLLVM 16+ (e.g. Debian's libllvm19); set "
                "DRJIT_LIBLLVM_PATH to its libLLVM.so"
            )
        fail(f"mitsuba variant {variant} unavailable: {e}{hint}")


class Skip(Exception):
    """A contender that cannot run this configuration (e.g. a sampler the build lacks)."""


@dataclass
class Sample:
    """One timed render: the image, render seconds, process wall and CPU seconds."""

    img: object
    render_s: float
    wall_s: float
    cpu_s: float


SAMPLER_TAG_RE = re.compile(r"""(<sampler\b[^>]*?\btype\s*=\s*)(["'])([^"']*)\2""")
SENSOR_OPEN_RE = re.compile(r"<sensor\b[^>]*?(?<!/)>")


def scene_sampler(xml: str) -> str | None:
    """The type of the first <sampler> element of a Mitsuba scene text, if any."""
    m = SAMPLER_TAG_RE.search(xml)
    return m.group(3) if m else None


def with_sampler(xml: str, sampler: str) -> str:
    """The scene text with every <sampler type="..."> changed to `sampler`; a scene without a
    sampler element gets one in its first sensor. Raise Skip if there is no sensor either."""
    out, n = SAMPLER_TAG_RE.subn(lambda m: f"{m.group(1)}{m.group(2)}{sampler}{m.group(2)}",
                                 xml)
    if n:
        return out
    out, n = SENSOR_OPEN_RE.subn(lambda m: f'{m.group(0)}<sampler type="{sampler}"/>', xml,
                                 count=1)
    if not n:
        raise Skip(f"no <sampler> or <sensor> element to give the sampler {sampler}")
    return out


class MitsubaContender:
    """One Mitsuba variant with one sampler, rendering in this process.

    The sampler is the scene file's own when `sampler` names its type; otherwise the scene
    text is loaded with its <sampler type="..."> changed (its parameters, sample_count and
    seed, are common to Mitsuba's samplers; a scene whose sampler has others is skipped)."""

    def __init__(self, mi, dr, variant: str, defines: dict[str, str],
                 sampler: str = "independent"):
        self.mi, self.dr, self.variant, self.defines = mi, dr, variant, defines
        self.name, self.sampler = f"mitsuba {variant}", sampler
        self.scene = None

    def setup(self, scene_path: Path) -> float:
        """Load the scene with this contender's sampler; return the loading time in s."""
        check_variant(self.mi, self.variant)
        self.mi.set_log_level(self.mi.LogLevel.Warn)
        xml = scene_path.read_text()
        t0 = time.perf_counter()
        try:
            if scene_sampler(xml) == self.sampler:
                self.scene = self.mi.load_file(str(scene_path), **self.defines)
            else:
                # load_string resolves relative file names (meshes, textures) through the
                # file resolver, which load_file would point at the scene's folder.
                resolver = (self.mi.file_resolver() if hasattr(self.mi, "file_resolver")
                            else self.mi.Thread.thread().file_resolver())
                resolver.prepend(str(scene_path.resolve().parent))
                self.scene = self.mi.load_string(with_sampler(xml, self.sampler),
                                                 **self.defines)
        except Exception as e:  # noqa: BLE001 (mitsuba raises RuntimeError and others)
            raise Skip(f"{self.name} {self.sampler} on {scene_path.name}: "
                       f"{str(e).strip().splitlines()[-1] if str(e).strip() else e!r}") from e
        return time.perf_counter() - t0

    def warmup(self, spp: int) -> float:
        """Render once untimed (JIT variants compile here); return its seconds."""
        self.mi.set_variant(self.variant)
        # Scalar variants compile nothing: a few samples warm the caches. JIT variants may
        # compile a kernel per sample count, so they warm up at the measured count.
        warm_spp = spp if self.dr.is_jit_v(self.mi.Float) else min(spp, 4)
        return self.render(warm_spp, WARMUP_SEED).render_s

    def render(self, spp: int, seed: int) -> Sample:
        """Render once, timed from mi.render until the image is evaluated."""
        import numpy as np

        self.mi.set_variant(self.variant)
        c0, t0 = time.process_time(), time.perf_counter()
        img = self.mi.render(self.scene, spp=spp, seed=seed)
        self.dr.eval(img)
        self.dr.sync_thread()
        dt, cpu = time.perf_counter() - t0, time.process_time() - c0
        return Sample(np.asarray(img, dtype=np.float64)[..., :3], dt, dt, cpu)


TIME_LINE_RE = re.compile(
    r"^time\s*[:=]?\s*([0-9]+(?:\.[0-9]*)?(?:[eE][-+]?\d+)?)\s*(ms|s)\b", re.MULTILINE)
TIME_RE = re.compile(r"\btime\s*[:=]?\s*([0-9]+(?:\.[0-9]*)?(?:[eE][-+]?\d+)?)\s*(ms|s)\b")
HEADER_RE = re.compile(r"integrator (\S+), \d+ [^(\n]*\((\w+)\)")


def parse_render_time(stdout: str) -> float | None:
    """The renderer's own render time, in seconds: the first line that starts with
    'time 1.234 s' (lines after it, such as BDPT's shares by path length and strategy, are
    ignored); failing that, the last 'time X s' anywhere."""
    m = TIME_LINE_RE.search(stdout)
    matches = [m.groups()] if m else TIME_RE.findall(stdout)
    if not matches:
        return None
    value, unit = matches[-1]
    return float(value) / (1000.0 if unit == "ms" else 1.0)


def parse_header(stdout: str) -> tuple[str, str] | None:
    """(integrator, sampler) from the render example's first line, e.g.
    'cornell-box: 256×256, integrator path, 64 spp (sobol), ...'; None if absent."""
    m = HEADER_RE.search(stdout)
    return (m.group(1), m.group(2)) if m else None


def children_cpu_s() -> float:
    """CPU seconds (user + system) used so far by finished child processes."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def split_sampler(args: list[str]) -> tuple[str | None, list[str]]:
    """Take '--sampler X' out of an argument list: (X or None, the other arguments)."""
    sampler, rest, it = None, [], iter(args)
    for a in it:
        if a == "--sampler":
            sampler = next(it, None)
        elif a.startswith("--sampler="):
            sampler = a.split("=", 1)[1]
        else:
            rest.append(a)
    return sampler, rest


class OursContender:
    """mcrt's render example with one sampler and extra arguments, run as a child process.

    `extra` may itself hold '--sampler X'; then X is the sampler (`sampler` is ignored).
    `independent` passes no --sampler: the scene file's sampler (independent in mcrt-render/tests/data)
    is used; the sampler the renderer reports on its first line is checked in setup()."""

    def __init__(self, binary: Path, sampler: str, extra: str, defines: dict[str, str],
                 threads: int, tmp: str, label: str = ""):
        self.binary, self.threads, self.tmp, self.label = binary, threads, tmp, label
        own, rest = split_sampler(shlex.split(extra))
        self.sampler = own or sampler
        self.sampler_args = [] if self.sampler == "independent" else [
            "--sampler", self.sampler]
        self.extra = rest
        for k, v in defines.items():
            self.extra += ["-D", f"{k}={v}"]
        self.name = f"mcrt{'@' + label if label else ''} {shlex.join(rest)}".strip()
        self.scene_path = None
        self.note = ""

    def key(self) -> tuple[str, str]:
        """What makes two contenders the same run."""
        return (self.name, self.sampler)

    def setup(self, scene_path: Path) -> float:
        """Run a 1-spp render (warms the page cache, checks the sampler); return its wall s."""
        self.scene_path = scene_path
        try:
            stdout, self.warm_s, _ = self._run(1, WARMUP_SEED)
        except RuntimeError as e:
            raise Skip(f"{self.name} --sampler {self.sampler} on {scene_path.name}: {e}") from e
        header = parse_header(stdout)  # (integrator, sampler) the renderer says it ran
        used = header[1] if header else self.sampler
        self.note = "" if used == self.sampler else f"(renderer reports sampler {used})"
        return self.warm_s

    def warmup(self, spp: int) -> float:
        """Nothing to compile: the 1-spp run of setup() was the warm-up; return its wall s."""
        return self.warm_s

    def render(self, spp: int, seed: int) -> Sample:
        """Render once; the render time is the one the binary prints."""
        stdout, wall, cpu = self._run(spp, seed)
        own = parse_render_time(stdout)
        if own is None:
            self.note = "(no render time printed: wall time used)"
        return Sample(read_exr(self._out()), own if own is not None else wall, wall, cpu)

    def _out(self) -> Path:
        tag = re.sub(r"[^A-Za-z0-9]+", "_", " ".join([self.label] + self.extra))[:80]
        return Path(self.tmp) / f"{self.scene_path.stem}-{self.sampler}{tag}.exr"

    def _run(self, spp: int, seed: int) -> tuple[str, float, float]:
        """Run the binary; return (stdout, wall s, CPU s) or raise RuntimeError."""
        cmd = [str(self.binary), str(self.scene_path), "--spp", str(spp),
               "--seed", str(seed), "-o", str(self._out())]
        cmd += self.sampler_args
        if self.threads:
            cmd += ["--threads", str(self.threads)]
        cmd += self.extra
        c0, t0 = children_cpu_s(), time.perf_counter()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall, cpu = time.perf_counter() - t0, children_cpu_s() - c0
        if p.returncode != 0:
            msg = (p.stderr.strip() or p.stdout.strip()).splitlines()
            raise RuntimeError(f"'{' '.join(cmd)}' failed: {msg[-1] if msg else p.returncode}")
        return p.stdout, wall, cpu


def build_renderer(binary: Path) -> None:
    """Build the render example in release mode (not timed)."""
    cmd = ["cargo", "build", "--release", "--bin", "render"]
    print("building:", " ".join(cmd), file=sys.stderr)
    if shutil.which("cargo") is None:
        fail("cargo not found; build the renderer yourself and pass --no-build")
    if subprocess.run(cmd, cwd=REPO).returncode != 0:
        fail("cargo build failed (is mcrt-render/src/bin/render.rs in this checkout?)")
    if not binary.exists():
        fail(f"the build did not produce {binary}")


# ---------------------------------------------------------------- images


def read_exr(path: Path):
    """Read an RGB EXR as a float64 array HxWx3 (with Mitsuba's Bitmap class)."""
    import drjit as dr
    import mitsuba as mi
    import numpy as np

    if not mi.variant():
        mi.set_variant("scalar_rgb")
    # With Dr.Jit's thread pool at one thread (--threads 1), reading an EXR file never
    # returns (Mitsuba 3.9.1): read with two, then restore.
    threads = dr.thread_count()
    if threads < 2:
        dr.set_thread_count(2)
    try:
        bmp = mi.Bitmap(str(path)).convert(
            mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False
        )
        return np.asarray(bmp, dtype=np.float64)
    finally:
        if threads < 2:
            dr.set_thread_count(threads)
