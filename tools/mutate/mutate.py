#!/usr/bin/env python3
"""Mutation testing for shadowlab's C++ (docs/mutation.md).

Generates mutants of the sources of one folder by text rules (tools/mutate/mutants.py), draws a
seeded sample, and for each one: writes the mutant, rebuilds the folder's test binary in a
build directory of its own, runs the binary (first failure stops it), and restores the source.
A mutant is killed when a test fails or the binary exceeds its time limit, stillborn when it
does not compile, and survives otherwise. Results go to a state file one line per mutant, so an
interrupted run resumes where it stopped; `--report` prints the per-folder table and every
survivor's diff, less the mutants listed as equivalent in tools/mutate/equivalent.txt.

  cmake -S . -B build-mut -DCMAKE_BUILD_TYPE=Release -DSHADOWLAB_UNITY=OFF -DSHADOWLAB_BOUNDS_TRAP=ON
  python3 tools/mutate/mutate.py --build build-mut --folder metric --sample 60
  python3 tools/mutate/mutate.py --build build-mut --report
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mutants import generate  # noqa: E402

PROGRAM = "mutate"
ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SOURCE_EXT = (".cpp", ".h", ".inl")
# The test binary that is each folder's specification (tests/CMakeLists.txt).
# The lab is tested through the programs too; the raster against Embree too; code that picks a
# kernel table by the process's ISA also on the narrower tables (docs/mutation.md).
FOLDER_TESTS = {"core": "test_core,test_core@scalar", "scenes": "test_scenes",
                "raster": "test_raster,test_raster@scalar,test_raster@avx2,test_raytrace",
                "raytrace": "test_raytrace", "metric": "test_metric",
                "techniques": "test_techniques,test_techniques@scalar,test_techniques@avx2", "util": "test_util",
                "lab": "test_lab,test_programs"}
EQUIVALENT_FILE = os.path.join(ROOT, "tools", "mutate", "equivalent.txt")


def fail(flag, reason):
    print(f"{PROGRAM}: {flag}: {reason}", file=sys.stderr)
    sys.exit(2)


def folder_files(folder):
    out = []
    for dirpath, _, names in os.walk(os.path.join(ROOT, folder)):
        for n in names:
            if n.endswith(SOURCE_EXT):
                out.append(os.path.relpath(os.path.join(dirpath, n), ROOT))
    return sorted(out)


def all_mutants(folder, files=None):
    out = []
    for rel in files or folder_files(folder):
        with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
            out += generate(rel, f.read())
    return out


def sample(mutants, n, seed):
    """The n mutants whose hash of (seed, id) is smallest: a mutant's place in the draw depends on
    its own id only, so an edit elsewhere in the folder adds or removes its own mutants and
    leaves the rest of the sample as it was."""
    def key(m):
        return hashlib.sha256(f"{seed}:{m.id}".encode()).hexdigest()
    order = sorted(mutants, key=key)
    return order if n is None else order[:n]


def load_state(path):
    """{id: the latest record}: a mutant run again (--retry-survivors) keeps its last result."""
    done = {}
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                line = line.strip()
                if line:
                    r = json.loads(line)
                    done[r["id"]] = r
    return done


def load_equivalent():
    eq = {}
    if os.path.exists(EQUIVALENT_FILE):
        with open(EQUIVALENT_FILE, encoding="utf-8") as f:
            for line in f:
                line = line.strip()
                if line and not line.startswith("#"):
                    mid, _, reason = line.partition(" ")
                    eq[mid] = reason.strip()
    return eq


def build(build_dir, targets, log):
    r = subprocess.run(["cmake", "--build", build_dir, "--target", *targets, "-j2"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if log and r.returncode:
        log.write(r.stdout[-4000:])
    return r.returncode == 0


# "BINARY@scalar" and "BINARY@avx2" in --test run the binary with the narrower kernel tables
# (docs/simd.md), so that code reached only through another table's choice is tested too.
ISA_ENV = {"scalar": ("SHADOWLAB_SCALAR", "1"), "avx2": ("SHADOWLAB_ISA", "avx2")}


def binaries_digest(build_dir, targets):
    """One hash of the test binaries' bytes: a mutant that leaves them all as they were (code in
    a preprocessor branch this build does not compile, or that the compiler folds to the same
    instructions) cannot change any output of this build."""
    paths = [os.path.join(build_dir, "tests", t) for t in targets]
    programs = os.path.join(build_dir, "programs")  # what test_programs runs
    if os.path.isdir(programs):
        paths += sorted(os.path.join(programs, n) for n in os.listdir(programs)
                        if os.path.isfile(os.path.join(programs, n)) and os.access(os.path.join(programs, n), os.X_OK))
    h = hashlib.sha256()
    for path in paths:
        h.update(path.encode())
        with open(path, "rb") as f:
            h.update(hashlib.sha256(f.read()).digest())
    return h.hexdigest()


def parse_runs(spec):
    """[(target, isa or None)] of a --test value, or a reason it is not one."""
    runs = []
    for item in spec.split(","):
        target, _, isa = item.partition("@")
        if not target or (isa and isa not in ISA_ENV):
            return None
        runs.append((target, isa or None))
    return runs


def run_tests(build_dir, runs, timeouts, gtest_filter):
    """Runs each binary in turn until one fails: (rc, [first failed test], seconds of each)."""
    times = []
    for (target, isa), timeout in zip(runs, timeouts):
        rc, failed, secs = run_binary(build_dir, target, isa, timeout, gtest_filter)
        times.append(secs)
        if rc != 0:
            return rc, failed, times
    return 0, [], times


def run_binary(build_dir, target, isa, timeout, gtest_filter):
    exe = os.path.join(build_dir, "tests", target)
    env = dict(os.environ)
    for name, _ in ISA_ENV.values():
        env.pop(name, None)
    if isa:
        env[ISA_ENV[isa][0]] = ISA_ENV[isa][1]
    cmd = [exe, "--gtest_fail_fast", "--gtest_brief=1"]
    if gtest_filter:
        cmd.append("--gtest_filter=" + gtest_filter)
    t0 = time.monotonic()
    try:
        r = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, timeout=timeout, env=env)
        rc, out = r.returncode, r.stdout
    except subprocess.TimeoutExpired as e:
        rc, out = "timeout", (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
    failed = [l.split("]", 1)[1].strip() for l in out.splitlines() if l.startswith("[  FAILED  ]")]
    return rc, failed[:1], time.monotonic() - t0


def describe(m, text):
    """One line before and after the edit."""
    ls = text.rfind("\n", 0, m.start) + 1
    le = text.find("\n", m.end)
    le = len(text) if le < 0 else le
    before = text[ls:le]
    after = text[ls:m.start] + m.replacement + text[m.end:le]
    return before.strip(), after.strip()


def run(a):
    if not os.path.isfile(os.path.join(a.build, "CMakeCache.txt")):
        fail("--build", f"'{a.build}' is not a configured CMake build folder")
    with open(os.path.join(a.build, "CMakeCache.txt"), encoding="utf-8", errors="replace") as f:
        cache = f.read()
    if "SHADOWLAB_UNITY:BOOL=OFF" not in cache:
        fail("--build", f"'{a.build}' compiles unity batches (each mutant would rebuild 16 files): "
             "configure it with -DSHADOWLAB_UNITY=OFF")
    if "SHADOWLAB_BOUNDS_TRAP:BOOL=ON" not in cache:
        fail("--build", f"'{a.build}' does not check array bounds (a mutant indexing past a fixed-size "
             "array would survive unseen): configure it with -DSHADOWLAB_BOUNDS_TRAP=ON")
    target = a.test or FOLDER_TESTS.get(a.folder.split("/")[0])
    if not target:
        fail("--folder", f"no test binary known for '{a.folder}' (give --test)")
    runs = parse_runs(target)
    if runs is None:
        fail("--test", f"'{target}' is not a comma-separated list of test binaries, each optionally "
             "followed by @scalar or @avx2")
    targets = sorted({t for t, _ in runs})
    files = folder_files(a.folder)
    if not files:
        fail("--folder", f"'{a.folder}' has no C++ sources")
    if a.no_headers:
        files = [f for f in files if f.endswith(".cpp")]
    mutants = sample(all_mutants(a.folder, files), a.sample, a.seed)
    if a.ids:  # only these of the draw (e.g. the survivors of an earlier draw, judged again)
        wanted = set(a.ids.split(","))
        mutants = [m for m in mutants if m.id in wanted]
        unknown = wanted - {m.id for m in mutants}
        if unknown:
            fail("--ids", f"{sorted(unknown)[0]}: no such mutant in the draw (its line changed, or "
                 "another folder's)")
    if a.list:
        for m in mutants:
            with open(os.path.join(ROOT, m.path), encoding="utf-8") as f:
                b, af = describe(m, f.read())
            print(f"{m.id} {m.path}:{m.line} [{m.rule}]\n  - {b}\n  + {af}")
        print(f"{len(mutants)} mutants")
        return 0
    state_path = a.state or os.path.join(a.build, "mutate_state.jsonl")
    backup = state_path + ".orig"
    if os.path.exists(backup):  # an interrupted run: put the source back first
        with open(backup, encoding="utf-8") as f:
            rec = json.load(f)
        with open(os.path.join(ROOT, rec["path"]), "w", encoding="utf-8") as f:
            f.write(rec["text"])
        os.remove(backup)
        print(f"{PROGRAM}: restored {rec['path']} from an interrupted run", file=sys.stderr)
    done = load_state(state_path)
    if a.retry_survivors:  # judge the survivors again, e.g. after new tests
        eq = load_equivalent()
        done = {k: r for k, r in done.items() if r["status"] != "survived" or k in eq}
    todo = [m for m in mutants if m.id not in done]
    log = open(state_path + ".buildlog", "a", encoding="utf-8")
    print(f"{PROGRAM}: {a.folder}: {len(mutants)} mutants drawn (seed {a.seed}), {len(todo)} to run, "
          f"tests: {target}", flush=True)
    if not build(a.build, targets, log):
        fail("--build", f"the unmutated sources do not build {target} (log: {state_path}.buildlog)")
    rc, failed, base = run_tests(a.build, runs, [None] * len(runs), a.gtest_filter)
    if rc != 0:
        fail("--folder", f"{target} fails before any mutation: {failed}")
    base_digest = binaries_digest(a.build, targets)
    timeouts = [max(10.0, a.timeout_factor * b) for b in base]
    print(f"{PROGRAM}: baseline {target} " + ", ".join(f"{b:.1f} s" for b in base) +
          "; limit " + ", ".join(f"{t:.0f} s" for t in timeouts), flush=True)
    with open(state_path, "a", encoding="utf-8") as state:
        for i, m in enumerate(todo):
            src = os.path.join(ROOT, m.path)
            with open(src, encoding="utf-8") as f:
                text = f.read()
            with open(backup, "w", encoding="utf-8") as f:
                json.dump({"path": m.path, "text": text}, f)
            before, after = describe(m, text)
            t0 = time.monotonic()
            try:
                with open(src, "w", encoding="utf-8") as f:
                    f.write(m.apply(text))
                if not build(a.build, targets, None):
                    status, detail = "stillborn", ""
                elif binaries_digest(a.build, targets) == base_digest:
                    status, detail = "same binary", "the test binaries are byte-identical to the unmutated ones"
                else:
                    rc, failed, _ = run_tests(a.build, runs, timeouts, a.gtest_filter)
                    status = "survived" if rc == 0 else "killed"
                    detail = "timeout" if rc == "timeout" else (failed[0] if failed else f"exit {rc}")
            finally:
                time.sleep(0.01)  # the restored file's time stamp must follow the mutant's object
                with open(src, "w", encoding="utf-8") as f:
                    f.write(text)
                os.remove(backup)
            rec = {"id": m.id, "folder": a.folder, "tests": target, "path": m.path, "line": m.line, "rule": m.rule,
                   "status": status, "detail": detail, "before": before, "after": after,
                   "seconds": round(time.monotonic() - t0, 1)}
            state.write(json.dumps(rec) + "\n")
            state.flush()
            print(f"[{i + 1}/{len(todo)}] {status:9s} {m.path}:{m.line} {m.rule} "
                  f"({rec['seconds']} s) {detail}", flush=True)
    build(a.build, targets, log)  # leave the build matching the sources
    return report(state_path)


def report(state_path, drawn=None):
    """The per-folder table and every survivor: of every result in the state file, or only of
    the mutants in `drawn` (a folder's draw; those not run yet are counted as such)."""
    done = load_state(state_path)
    eq = load_equivalent()
    folders = {}
    if drawn is not None:
        missing = [m for m in drawn if m.id not in done]
        done = {m.id: done[m.id] for m in drawn if m.id in done}
        if missing:
            print(f"{len(missing)} of the {len(drawn)} drawn mutants have no result yet")
    for r in done.values():
        f = folders.setdefault(r["folder"], {"mutants": 0, "stillborn": 0, "killed": 0,
                                             "equivalent": 0, "survived": []})
        f["mutants"] += 1
        if r["status"] == "stillborn":
            f["stillborn"] += 1
        elif r["status"] == "killed":
            f["killed"] += 1
        elif r["id"] in eq or r["status"] == "same binary":
            f["equivalent"] += 1
        else:
            f["survived"].append(r)
    print(f"{'folder':12s} {'mutants':>7s} {'stillborn':>9s} {'killed':>6s} {'equivalent':>10s} "
          f"{'survived':>8s} {'survived %':>10s}")
    for name, f in sorted(folders.items()):
        live = f["mutants"] - f["stillborn"] - f["equivalent"]
        pct = 100.0 * len(f["survived"]) / live if live else 0.0
        print(f"{name:12s} {f['mutants']:7d} {f['stillborn']:9d} {f['killed']:6d} {f['equivalent']:10d} "
              f"{len(f['survived']):8d} {pct:9.1f}%")
    for name, f in sorted(folders.items()):
        for r in sorted(f["survived"], key=lambda r: (r["path"], r["line"])):
            print(f"\nsurvived {r['id']} {r['path']}:{r['line']} [{r['rule']}]\n  - {r['before']}\n  + {r['after']}")
    return 0


def main(argv=None):
    p = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.splitlines()[0])
    p.add_argument("--build", required=True, help="a configured CMake build folder used only for this")
    p.add_argument("--folder", help="a source folder: " + ", ".join(sorted(FOLDER_TESTS)) + " (or a sub-folder)")
    p.add_argument("--test", help="test binary targets, comma-separated, run in turn (default: the folder's); "
                   "BINARY@scalar or BINARY@avx2 runs it with those kernel tables")
    p.add_argument("--gtest-filter", help="run only these tests of the binary")
    p.add_argument("--sample", type=int, help="draw this many mutants (default: all)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--ids", help="run only these mutants of the draw, comma-separated ids")
    p.add_argument("--state", help="results file (default BUILD/mutate_state.jsonl)")
    p.add_argument("--timeout-factor", type=float, default=4.0)
    p.add_argument("--no-headers", action="store_true", help="mutate .cpp files only")
    p.add_argument("--retry-survivors", action="store_true",
                   help="run the drawn mutants that survived before again (after adding tests)")
    p.add_argument("--list", action="store_true", help="print the drawn mutants and stop")
    p.add_argument("--report", action="store_true",
                   help="print the table of the state file (with --folder: of that draw) and stop")
    a = p.parse_args(argv)
    if a.sample is not None and a.sample < 1:
        fail("--sample", f"{a.sample}: must be at least 1")
    if a.timeout_factor <= 1:
        fail("--timeout-factor", f"{a.timeout_factor}: must exceed 1")
    if a.report:
        drawn = None
        if a.folder:  # the table of this folder's draw only
            files = folder_files(a.folder)
            if a.no_headers:
                files = [f for f in files if f.endswith(".cpp")]
            drawn = sample(all_mutants(a.folder, files), a.sample, a.seed)
        return report(a.state or os.path.join(a.build, "mutate_state.jsonl"), drawn)
    if not a.folder:
        fail("--folder", "needed unless --report")
    if not os.path.isdir(os.path.join(ROOT, a.folder)):
        fail("--folder", f"'{a.folder}' is not a folder of the repository")
    return run(a)


if __name__ == "__main__":
    sys.exit(main())
