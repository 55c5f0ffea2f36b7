"""The engine's compilation, measured: what the workflow's rules ``compile_engine_parts`` (what the step
loop, the driver and the scan call, which the workflow runs beside the next), ``compile_engine`` (the step loop
and the threshold scans, loading those parts) and ``compile_engine_more`` (the rest, after it) compile —
their script, called with a stand-in for Snakemake's object and one numba thread, as the rules run it (with
room on Python's frame stack, ``rockstudy.core.frames``) — into an empty numba cache, with the CPU time of
each compiled function.

    python benchmarks/compile_time.py [--config config.yaml] [--top 15] [--cache DIR] [--no-frame-room]
                                      [--side-by-side | --part parts|scan|more]

By default the three parts run one after the other in this process. ``--side-by-side`` runs them as the
workflow does on two cores: ``compile_engine_parts`` in a second process at the same time as
``compile_engine`` in this one, then ``compile_engine_more``; the wall time of ``compile_engine`` is then
what the spectra wait for (the functions listed are this process's).

Prints the CPU (its system part apart) and wall time of each part and, for the ``--top`` most expensive compiled
functions, the CPU time spent compiling each one alone (``own``: without the functions it calls, which are
compiled first) and with them (``with callees``); then where this process's compile went: LLVM (optimising and
emitting machine code, numba's ``numba:llvm_lock`` events), numba's inlining of the functions compiled
``inline=`` into their callers (each call site translates the callee's byte code again and copies its IR) and
the rest of numba's own front end (typing, lowering). ``--cache`` keeps the cache in ``DIR`` (emptied
first) instead of a temporary folder. ``--part parts|scan|more`` compiles that part alone into ``--cache`` as
it finds it (not emptied: ``--side-by-side`` runs its second process so), e.g. the scans alone on an empty
cache. ``--no-frame-room`` calls the scripts without that room, as a plain call does: numba's compiler then
takes and gives back a chunk of the frame stack wherever its calls cross a chunk's end, which shows as system
time. The machine is shared: compare two versions back to back (another version's ``src`` first on
``PYTHONPATH``), not with figures from another session.
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import SimpleNamespace

ROOT = Path(__file__).resolve().parents[1]
PARTS = {"parts": "compile_engine_parts", "scan": "compile_engine", "more": "compile_engine_more"}
"""The parts of the compile (``params.part``) and the workflow's rules that compile them."""


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--config", type=Path, default=ROOT / "config.yaml")
    ap.add_argument("--top", type=int, default=15, help="compiled functions listed (default 15)")
    ap.add_argument("--cache", type=Path, default=None,
                    help="numba cache folder, emptied first (default: a temporary one)")
    ap.add_argument("--no-frame-room", action="store_true",
                    help="call the scripts without room on the frame stack (rockstudy.core.frames)")
    ap.add_argument("--side-by-side", action="store_true",
                    help="compile_engine_parts in a second process beside compile_engine, as the workflow runs them")
    ap.add_argument("--part", choices=PARTS,
                    help="compile this part alone, into --cache as it is (empty it first to measure a part alone)")
    return ap.parse_args(argv)


def compile_times():
    """A listener to numba's "numba:compile" events: CPU time per compiled function, own and inclusive."""
    from numba.core.event import Listener

    class CompileTimes(Listener):
        def __init__(self):
            self.stack, self.own, self.inclusive = [], {}, {}

        def on_start(self, event):
            self.stack.append([event.data["dispatcher"].py_func.__qualname__, time.process_time(), 0.0])

        def on_end(self, event):
            name, start, callees = self.stack.pop()
            spent = time.process_time() - start
            self.inclusive[name] = self.inclusive.get(name, 0.0) + spent
            self.own[name] = self.own.get(name, 0.0) + spent - callees
            if self.stack:
                self.stack[-1][2] += spent

    return CompileTimes()


class OutermostCPU:
    """The CPU time spent in the outermost of nested calls (``enter`` ... ``leave``) and the number of calls."""

    def __init__(self):
        self.depth, self.start, self.cpu, self.calls = 0, 0.0, 0.0, 0

    def enter(self):
        if self.depth == 0:
            self.start = time.process_time()
        self.depth += 1
        self.calls += 1

    def leave(self):
        self.depth -= 1
        if self.depth == 0:
            self.cpu += time.process_time() - self.start


def watch_llvm_and_inlining():
    """(LLVM, inlining): the CPU time of LLVM's work (numba's "numba:llvm_lock" events) and of numba's inlining
    of ``inline=`` functions (``InlineWorker.inline_function``, wrapped for this process), from now on."""
    from numba.core import event, inline_closurecall

    llvm, inlining = OutermostCPU(), OutermostCPU()

    class LLVM(event.Listener):
        def on_start(self, event):
            llvm.enter()

        def on_end(self, event):
            llvm.leave()

    event.register("numba:llvm_lock", LLVM())
    inline_function = inline_closurecall.InlineWorker.inline_function

    def timed(self, *args, **kwargs):
        inlining.enter()
        try:
            return inline_function(self, *args, **kwargs)
        finally:
            inlining.leave()

    inline_closurecall.InlineWorker.inline_function = timed
    return llvm, inlining


def main(argv=None) -> int:
    args = parse(argv)
    cache = args.cache or Path(tempfile.mkdtemp(prefix="rockstudy-numba-"))
    if args.part is None:
        shutil.rmtree(cache, ignore_errors=True)
        cache.mkdir(parents=True)
    os.environ["NUMBA_CACHE_DIR"] = str(cache)  # before numba is imported
    import yaml
    from numba.core import event

    from rockstudy.core.frames import with_frame_room
    from rockstudy.studies import expectations, parameters

    config = yaml.safe_load(args.config.read_text(encoding="utf-8"))
    levels = config["noise_levels"]
    free = parameters.noise_free_level(levels)
    level = next((name for name in levels if name != free), free)  # as the rule: the first noisy level
    spec = importlib.util.spec_from_file_location("compile_engine", ROOT / "workflow/scripts/compile_engine.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    scenario = expectations.scenario_spec(config, "CS01", level, 0.0, 0.0)
    listener = compile_times()
    llvm, inlining = watch_llvm_and_inlining()
    with tempfile.TemporaryDirectory() as tmp, event.install_listener("numba:compile", listener):
        beside = None
        if args.part:
            order = [args.part]
        elif args.side_by_side:  # the parts in a second process, started now, beside the scans here
            command = [sys.executable, __file__, "--config", str(args.config), "--cache", str(cache), "--part", "parts"]
            beside = subprocess.Popen(command + (["--no-frame-room"] if args.no_frame_room else []),
                                      stdout=subprocess.PIPE, text=True)
            order = ["scan", "more"]
        else:
            order = ["parts", "scan", "more"]
        for part in order:
            rule = PARTS[part]
            if part == "more" and beside is not None:
                print(beside.communicate()[0].splitlines()[0], flush=True)
                if beside.returncode:
                    raise SystemExit(f"compile_engine_parts failed (exit status {beside.returncode})")
            stand_in = SimpleNamespace(log=[f"{tmp}/{part}.log"], output=[f"{tmp}/{part}.done"], threads=1,
                                       params=SimpleNamespace(scenario=scenario, library="benchmark", part=part))
            cpu, system, wall = time.process_time(), os.times().system, time.perf_counter()
            if args.no_frame_room:
                script.main(stand_in)
            else:
                with_frame_room(script.main, stand_in)
            if args.part:
                where = "in its own process, on the given cache"
            elif part == "scan" and beside is not None:
                where = "on an empty cache, compile_engine_parts beside it"
            else:
                where = "on an empty cache" if part == "parts" else "on that cache"
            print(f"{rule} ({part}) {where}: "
                  f"{time.process_time() - cpu:.1f} s CPU (system {os.times().system - system:.1f} s), "
                  f"{time.perf_counter() - wall:.1f} s wall", flush=True)
    n_files = len(list(cache.rglob("*.nbc")))
    if args.cache is None:
        shutil.rmtree(cache, ignore_errors=True)
    print(f"{len(listener.own)} functions compiled, {n_files} compiled objects cached")
    print(f"{'function':32s} {'own':>7s} {'with callees':>13s}  [s CPU]")
    for name in sorted(listener.own, key=listener.own.get, reverse=True)[:args.top]:
        print(f"{name:32s} {listener.own[name]:7.2f} {listener.inclusive[name]:13.2f}")
    compiled = sum(listener.own.values())
    print(f"this process compiled for {compiled:.1f} s CPU: LLVM {llvm.cpu:.1f} s, numba's inlining "
          f"{inlining.cpu:.1f} s ({inlining.calls} call sites, nested ones counted), "
          f"the rest of numba's front end {compiled - llvm.cpu - inlining.cpu:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
