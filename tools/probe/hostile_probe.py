#!/usr/bin/env python3
"""The hostile-but-fair probe of issue 26: tmlab's commands tried as a new user would, with bad
input, awkward places for results, signals and a full disk, each outcome judged good / weak / bad.

    python3 tools/probe/hostile_probe.py --tmlab build/release/apps/tmlab/tmlab --out DIR [--only ID,..]

One table of cases (CASES below). Each case has an id, what it tries, how it is set up (a function
that makes its files in its own folder, and may run tmlab to make a previous result), the command
(an argument vector: nothing here ever goes through a shell), and its rule: a function that judges the
outcome
    bad  = data loss, a crash or a signal exit, a stale RUNNING, a hang, a silently wrong result;
    weak = accepted but should be refused, or refused with an unclear message;
    good = a named refusal, or the correct result.
The probe prints a markdown table (id, case, outcome, verdict) and the counts, writes DIR/probe.json,
and exits 0: it is a report, not a test (tests of the rules are in apps/tmlab/tests). Python 3
standard library only. See tools/probe/README.md.
"""

import argparse
import dataclasses
import hashlib
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Callable, Dict, List, Optional, Tuple

GOOD, WEAK, BAD = "good", "weak", "bad"

# ---------------------------------------------------------------------------------------------------
# Running tmlab


@dataclasses.dataclass
class Outcome:
    rc: Optional[int]  # exit status; -N when signal N ended it; None when it hung (killed)
    raw: bytes = b""  # stdout + stderr
    seconds: float = 0.0
    case_dir: str = ""  # the case's folder: shown as <case> so that its name never matches a rule's word

    @property
    def out(self) -> str:
        text = self.raw.decode("utf-8", "replace")
        return text.replace(self.case_dir, "<case>") if self.case_dir else text

    def first_line(self) -> str:
        lines = [l.strip() for l in self.out.splitlines() if l.strip() and "see 'tmlab help'" not in l]
        for line in lines:
            if line.startswith("tmlab") and ("error" in line or ": --" in line or "refus" in line):
                return line
        for line in lines:
            if "error:" in line.lower() or "refus" in line.lower():
                return line
        return lines[-1] if lines else ""


class Ctx:
    """The probe's settings and shared inputs (made lazily, once)."""

    def __init__(self, tmlab: Path, source: Path, work: Path):
        self.tmlab = tmlab
        self.source = source
        self.work = work
        self.dir = work  # the current case's folder
        self._phantom: Optional[Path] = None

    def env(self, extra: Optional[Dict[str, str]] = None) -> Dict[str, str]:
        e = dict(os.environ)
        e["TMLAB_ROOT"] = str(self.source)
        e.pop("TMLAB_TEST_STOP_AFTER_PROGRESS", None)
        e.update(extra or {})
        return e

    def run(self, args: List[str], cwd: Optional[Path] = None, timeout: float = 600,
            env: Optional[Dict[str, str]] = None, limit_memory: Optional[int] = None,
            prefix: Optional[List[str]] = None) -> Outcome:
        """tmlab args... (an argument vector), in `cwd`, killed after `timeout` seconds."""
        argv = (prefix or []) + [str(self.tmlab)] + [str(a) for a in args]

        def limits():
            if limit_memory:
                resource.setrlimit(resource.RLIMIT_AS, (limit_memory, limit_memory))

        t0 = time.monotonic()
        p = subprocess.Popen(argv, cwd=str(cwd or self.dir), env=self.env(env), stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, start_new_session=True,
                             preexec_fn=limits if limit_memory else None)
        try:
            raw, _ = p.communicate(timeout=timeout)
            return Outcome(p.returncode, raw, time.monotonic() - t0, str(self.dir))
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            raw, _ = p.communicate()
            return Outcome(None, raw, time.monotonic() - t0, str(self.dir))

    def signalled(self, args: List[str], wait_for: Path, sig: int, bound: float = 60,
                  env: Optional[Dict[str, str]] = None, delay: float = 0.0) -> Outcome:
        """Starts tmlab args..., waits (up to 300 s) until `wait_for` exists, then `delay` seconds,
        sends `sig` to it, and waits up to `bound` seconds for it to end (then kills it: rc None)."""
        log = self.dir / "signalled.log"
        with open(log, "wb") as f:
            p = subprocess.Popen([str(self.tmlab)] + [str(a) for a in args], cwd=str(self.dir),
                                 env=self.env(env), stdout=f, stderr=subprocess.STDOUT, start_new_session=True)
            t0 = time.monotonic()
            while not wait_for.exists() and p.poll() is None and time.monotonic() - t0 < 300:
                time.sleep(0.05)
            if p.poll() is None:
                time.sleep(delay)
                p.send_signal(sig)
                t1 = time.monotonic()
                try:
                    p.wait(timeout=bound)
                    rc = p.returncode
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait()
                    rc = None
                seconds = time.monotonic() - t1
            else:
                rc, seconds = p.returncode, 0.0
        return Outcome(rc, log.read_bytes(), seconds, str(self.dir))

    # -- shared inputs --------------------------------------------------------------------------
    def raw_phantom(self) -> Path:
        return self.source / "calibration" / "data" / "phantom" / "EF10_0T" / "EF10_0T_A1.csv"

    def phantom(self) -> Path:
        """The phantom A1 test converted to tmlab-measured/1 (once)."""
        if self._phantom is None:
            d = self.work / "_shared" / "phantom"
            o = self.run(["data", "convert", self.raw_phantom(), "--out", d], cwd=self.work)
            if o.rc != 0:
                raise RuntimeError("cannot convert the phantom: " + o.out)
            self._phantom = d / "EF10_0T_A1.csv"
        return self._phantom

    def copy_phantom(self, name: str = "A1") -> Path:
        """A private copy of the converted phantom as DIR/NAME.csv + .json (name in the JSON too)."""
        src = self.phantom()
        csv = self.dir / "data" / (name + ".csv")
        csv.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(src, csv)
        meta = json.loads(strip_comments(src.with_suffix(".json").read_text()))
        meta["name"] = name
        csv.with_suffix(".json").write_text(json.dumps(meta, indent=1))
        return csv


def strip_comments(text: str) -> str:
    return "\n".join(l for l in text.splitlines() if not l.lstrip().startswith("//"))


def tiny(dir_: Path, name: str = "tiny", ripple: bool = True, sign: float = 1.0, meta: Optional[dict] = None) -> Path:
    """A tiny tmlab-measured/1 set: a cylinder (R 25 mm, H 30 mm, frictionless platens) compressed
    to 10 % strain, linear, E = 20 kPa; with `ripple` a deterministic +-0.5 % so that fits have a
    residual; `sign` -1 flips the force (the wrong sign convention)."""
    dir_.mkdir(parents=True, exist_ok=True)
    m = {"format": "tmlab-measured/1", "name": name, "test": "unconfined_compression",
         "sample": {"shape": "cylinder", "radius_m": 0.025, "height_m": 0.03, "bottom": "frictionless",
                    "platens": "frictionless"}, "source": "the hostile probe"}
    if meta is not None:
        m = meta
    (dir_ / (name + ".json")).write_text(json.dumps(m, indent=1))
    area = 3.141592653589793 * 0.025 ** 2
    rows = ["time_s,displacement_m,force_N"]
    for i in range(40):
        d = 0.003 * i / 39
        r = 1 + (0.005 * (((i * 7) % 5) - 2) / 2 if ripple else 0)
        rows.append("%.6f,%.9g,%.9g" % (0.45 * i, d, sign * 20000 * area * d / 0.03 * r))
    (dir_ / (name + ".csv")).write_text("\n".join(rows) + "\n")
    return dir_ / (name + ".csv")


# ---------------------------------------------------------------------------------------------------
# Judging helpers


def snapshot(*roots: Path) -> Dict[str, str]:
    """path -> 'dir' | 'link:<target>' | sha256 of the bytes, for every entry under the roots."""
    s: Dict[str, str] = {}
    for root in roots:
        if not os.path.lexists(root):
            continue
        todo = [root]
        while todo:
            p = todo.pop()
            if p.is_symlink():
                s[str(p)] = "link:" + os.readlink(p)
            elif p.is_dir():
                s[str(p)] = "dir"
                todo.extend(p.iterdir())
            elif p.is_file():
                s[str(p)] = hashlib.sha256(p.read_bytes()).hexdigest()
            else:
                s[str(p)] = "special"
    return s


def lost(before: Dict[str, str], after: Dict[str, str]) -> List[str]:
    return [p for p, h in before.items() if after.get(p) != h]


def find(root: Path, name: str) -> List[Path]:
    out = []
    for dirpath, dirnames, filenames in os.walk(root, followlinks=True):
        if name in filenames or name in dirnames:
            out.append(Path(dirpath) / name)
    return out


def crashed(o: Outcome) -> Optional[Tuple[str, str]]:
    """bad when tmlab hung, died by a signal, or reported an internal error."""
    if o.rc is None:
        return BAD, "hung (killed after the time limit)"
    if o.rc < 0:
        return BAD, "killed by signal %d" % -o.rc
    if o.rc in (128 + signal.SIGSEGV, 128 + signal.SIGABRT, 128 + signal.SIGBUS, 128 + signal.SIGFPE):
        return BAD, "crashed (%s)" % signal.Signals(o.rc - 128).name
    if o.rc > 2 and o.rc not in (130, 143):
        return BAD, "exit %d" % o.rc
    if "internal error" in o.out:
        return BAD, "internal error: " + o.first_line()
    return None


def refused(o: Outcome, *words: str, codes=(1, 2)) -> Tuple[str, str]:
    """good: refused naming `words`; weak: refused without them; bad: crash; weak: accepted."""
    c = crashed(o)
    if c:
        return c
    if o.rc == 0:
        return WEAK, "accepted (exit 0)"
    missing = [w for w in words if w.lower() not in o.out.lower()]
    if o.rc not in codes:
        return WEAK, "exit %d" % o.rc
    if missing:
        return WEAK, "refused without naming %s: %s" % (", ".join(missing), o.first_line())
    return GOOD, "refused: " + o.first_line()


def refused_keeping(o: Outcome, s: dict, *words: str) -> Tuple[str, str]:
    """refused (as above), and nothing the user had (s['before'], s['roots']) lost or changed."""
    gone = lost(s["before"], snapshot(*s["roots"]))
    if gone:
        return BAD, "data loss: %d of the user's files removed or changed (%s)" % (
            len(gone), ", ".join(Path(g).name for g in gone[:4]))
    return refused(o, *words)


def complete(d: Path) -> List[str]:
    """What keeps `d` from being a complete result under the new protocol ([] when complete)."""
    why = []
    if not (d / "summary.json").is_file():
        why.append("no summary.json")
    for m in ("RUNNING", "FAILED", "INTERRUPTED", ".incomplete"):
        if (d / m).exists():
            why.append(m + " left")
    if not (d / ".tmlab-result").is_file():
        why.append("no .tmlab-result marker")
    return why


def result_rule(result_key: str, symlink: bool = False):
    """good: a complete result at s[result_key], nothing of the user's lost (and a symlink kept)."""

    def rule(ctx: Ctx, s: dict, o: Outcome) -> Tuple[str, str]:
        c = crashed(o)
        if c:
            return c
        gone = lost(s.get("before", {}), snapshot(*s.get("roots", [])))
        if gone:
            return BAD, "data loss: " + ", ".join(Path(g).name for g in gone[:4])
        d = s[result_key]
        if find(ctx.dir, "RUNNING"):
            return BAD, "stale RUNNING"
        if symlink and not Path(s["link"]).is_symlink():
            return BAD, "the symlink was replaced by a directory"
        if o.rc != 0:
            return (BAD if "cross-device" in o.out or "busy" in o.out else WEAK), "exit %d: %s" % (o.rc, o.first_line())
        why = complete(d)
        if why:
            return WEAK, "exit 0 but " + ", ".join(why)
        return GOOD, "complete result"

    return rule


def protect(ctx: Ctx, s: dict, *roots: Path) -> dict:
    s["roots"] = list(roots)
    s["before"] = snapshot(*roots)
    return s


def foreign_files(d: Path, manifest: bool = True) -> None:
    (d / "data").mkdir(parents=True, exist_ok=True)
    if manifest:
        (d / "manifest.json").write_text("{}\n")
    (d / "thesis.tex").write_text("\\chapter{Results}\n")
    (d / "data" / "raw.csv").write_text("t,f\n0,1\n")


# ---------------------------------------------------------------------------------------------------
# The cases


@dataclasses.dataclass
class Case:
    id: str
    tries: str
    setup: Callable[[Ctx], dict]
    command: Callable[[Ctx, dict], object]  # an argument vector, or a callable returning an Outcome
    rule: Callable[[Ctx, dict, Outcome], Tuple[str, str]]
    issue: str = ""  # the issue-26 item it covers ("bad 1", "weak: ...", "good: ...", "property")


def fit_args(csv: Path, out: Path, *extra: str, starts: str = "2") -> List[str]:
    return ["fit", str(csv), "--model", "neo_hookean", "--starts", starts, "--local-runs", "1", "--no-profile",
            "--no-plots", "--quiet", "--out", str(out)] + list(extra)


def disc_args(csv: Path, out: Path, *extra: str) -> List[str]:
    return ["discover", str(csv), "--rounds", "1", "--starts", "2", "--no-plots", "--quiet", "--out",
            str(out)] + list(extra)


def run_args(res: Path, *extra: str) -> List[str]:
    return ["run", "cube-uniaxial", "--no-plots", "--results", str(res)] + list(extra)


# -- bad 1: a foreign manifest.json, crafted markers, a user's file in a result ---------------------

def s_foreign_fit(ctx):
    v = ctx.dir / "V"
    foreign_files(v)
    return protect(ctx, {"csv": tiny(ctx.dir / "d")}, v)


def s_foreign_run(ctx):
    v = ctx.dir / "res" / "cube-uniaxial"
    foreign_files(v)
    return protect(ctx, {}, v)


def s_crafted_marker(ctx):
    v = ctx.dir / "V"
    v.mkdir()
    (ctx.dir / "victim.txt").write_text("outside\n")
    (ctx.dir / "victim2.txt").write_text("absolute\n")
    (v / "summary.json").write_text("{}\n")
    (v / ".tmlab-result").write_text(json.dumps(
        {"format": "tmlab-result/1", "run_id": "x", "files": ["../victim.txt", str(ctx.dir / "victim2.txt")]}))
    return protect(ctx, {"csv": tiny(ctx.dir / "d")}, ctx.dir / "victim.txt", ctx.dir / "victim2.txt", v)


def s_crafted_manifest(ctx):
    # The old protocol's ownership sign: a manifest.json with "files" reaching outside.
    v = ctx.dir / "V"
    v.mkdir()
    (ctx.dir / "victim.txt").write_text("outside\n")
    (v / "manifest.json").write_text(json.dumps({"files": ["../victim.txt", "/etc/hostname"]}))
    (v / "summary.json").write_text(json.dumps({"status": "complete", "files": ["../victim.txt"]}))
    return protect(ctx, {"csv": tiny(ctx.dir / "d")}, ctx.dir / "victim.txt", v)


def s_previous_plus_user_file(ctx):
    csv = tiny(ctx.dir / "d")
    out = ctx.dir / "V"
    o = ctx.run(fit_args(csv, out))
    if o.rc != 0:
        raise RuntimeError("setup fit failed: " + o.out)
    (out / "my-notes.txt").write_text("written by the user into the result folder\n")
    return protect(ctx, {"csv": csv}, out / "my-notes.txt")


def s_previous_complete(ctx):
    csv = tiny(ctx.dir / "d")
    out = ctx.dir / "V"
    if ctx.run(fit_args(csv, out)).rc != 0:
        raise RuntimeError("setup fit failed")
    (ctx.dir / "beside.txt").write_text("sibling\n")
    return protect(ctx, {"csv": csv, "out": out}, ctx.dir / "beside.txt", ctx.dir / "d")


def s_previous_interrupted(ctx):
    csv = tiny(ctx.dir / "d")
    out = ctx.dir / "V"
    o = ctx.run(fit_args(csv, out, "--checkpoint-every", "1"), env={"TMLAB_TEST_STOP_AFTER_PROGRESS": "1:SIGINT"})
    if o.rc != 130:
        raise RuntimeError("setup: the fit was not interrupted: " + o.out)
    return protect(ctx, {"csv": csv, "out": out}, ctx.dir / "d")


# -- bad 2 / 3: symlinks, `.`, "" -------------------------------------------------------------------

def s_symlink(ctx, other_fs: bool):
    base = Path("/dev/shm") if other_fs and Path("/dev/shm").is_dir() else ctx.dir
    target = base / ("tmlab_probe_%d_%s" % (os.getpid(), ctx.dir.name)) / "target"
    target.mkdir(parents=True)
    (target.parent / "beside.txt").write_text("someone's\n")
    link = ctx.dir / "link"
    link.symlink_to(target)
    s = {"csv": tiny(ctx.dir / "d"), "link": link, "target": target, "cleanup": target.parent}
    if other_fs and os.stat(base).st_dev == os.stat(ctx.dir).st_dev:
        s["note"] = "(no other file system: /dev/shm is the same)"
    return protect(ctx, s, target.parent)


def s_cwd(ctx):
    cwd = ctx.dir / "cwd"
    foreign_files(cwd)
    return protect(ctx, {"csv": tiny(ctx.dir / "d"), "cwd": cwd}, cwd)


# -- bad 7: a full disk -----------------------------------------------------------------------------

def full_disk(ctx: Ctx, args_for: Callable[[Path], List[str]], size: int = 131072, fill: bool = True) -> Outcome:
    """Runs tmlab with its output on a `size`-byte tmpfs, filled to two free pages by a file of
    someone's, mounted at ctx.dir/disk in a private mount namespace (unshare; this script re-invoked
    as the helper, an argument vector throughout)."""
    mnt = ctx.dir / "disk"
    mnt.mkdir()
    unshare = shutil.which("unshare")
    if not unshare:
        return Outcome(-999, b"unshare not found: cannot make a full disk")
    prefix = [unshare, "--mount", "--propagation", "private"]
    if os.geteuid() != 0:
        prefix[1:1] = ["--user", "--map-root-user"]
    prefix += ["--", sys.executable, os.path.abspath(__file__), "--full-disk-helper", str(mnt), str(size),
               "fill" if fill else "nofill", "--"]
    return ctx.run(args_for(mnt), prefix=prefix)


def full_disk_rule(result: Callable[[Ctx], Path]):
    def rule(ctx, s, o):
        if o.rc == -999 or "cannot mount" in o.out:
            return WEAK, "not tried: " + o.first_line()
        c = crashed(o)
        if c:
            return c
        # The tmpfs is gone with its namespace: the helper left what was on it in disk.state.json.
        st = json.loads((ctx.dir / "disk.state.json").read_text())
        rel = os.path.relpath(result(ctx), ctx.dir / "disk")
        files = {f for f in st["files"] if f == rel or f.startswith(rel + "/")}
        if rel + "/RUNNING" in files:
            return BAD, "RUNNING left after the process ended%s: %s" % (
                "" if rel + "/FAILED" in files else " (no FAILED)", o.first_line())
        if "filler.bin" not in st["files"] or st.get("filler_changed"):
            return BAD, "data loss: the file filling the disk was removed or changed"
        if o.rc == 0:
            missing = [m for m in ("summary.json", ".tmlab-result") if rel + "/" + m not in files]
            return (GOOD, "fits on the small disk: complete") if not missing else (
                BAD if "summary.json" in missing else WEAK, "exit 0 on a full disk without " + ", ".join(missing))
        if "HDF5-DIAG" in o.out:
            return WEAK, "FAILED, but HDF5 error-stack noise on stderr"
        if rel + "/FAILED" not in files:
            return WEAK, "exit %d without FAILED: %s" % (o.rc, o.first_line())
        if "space" not in st["failed"].get(rel + "/FAILED", "").lower():
            return WEAK, "FAILED without naming the full disk"
        return GOOD, "FAILED with the reason: " + o.first_line()

    return rule


# -- signals ----------------------------------------------------------------------------------------

def signal_rule(result: Callable[[Ctx, dict], Path], sig: int):
    def rule(ctx, s, o):
        d = result(ctx, s)
        if o.rc is None:
            return BAD, "%s ignored: still running after 60 s (killed)" % signal.Signals(sig).name
        if find(ctx.dir, "RUNNING"):
            return BAD, "stale RUNNING"
        if o.rc == 0:
            return BAD, "%s ignored: ran to the end and reported a complete result" % signal.Signals(sig).name
        if o.rc != 128 + sig:
            return BAD, "exit %s" % o.rc
        if not (d / "INTERRUPTED").exists() or (d / "summary.json").exists():
            return WEAK, "exit %d but no INTERRUPTED marker (or a summary.json)" % o.rc
        return GOOD, "stopped in %.1f s: INTERRUPTED, exit %d" % (o.seconds, o.rc)

    return rule


def without_times(j):
    if isinstance(j, dict):
        return {k: without_times(v) for k, v in j.items()
                if k not in ("seconds", "wall_seconds", "generated_utc", "command_line", "started_utc",
                             "finished_utc", "run_id", "resumed", "checkpoint")}
    if isinstance(j, list):
        return [without_times(v) for v in j]
    return j


def resume_case(kind: str, sig: int):
    """setup: an uninterrupted run and an interrupted one (SIGINT/SIGTERM at the first checkpoint,
    through TMLAB_TEST_STOP_AFTER_PROGRESS; SIGKILL from outside after a checkpoint exists)."""

    def args(ctx, out):
        if kind == "fit":
            return fit_args(ctx.dir / "d" / "tiny.csv", out)
        if kind == "discover":
            return disc_args(ctx.dir / "d" / "tiny.csv", out)
        return ["run", "cantilever-explicit", "--no-plots", "--results", str(out)]

    def setup(ctx):
        tiny(ctx.dir / "d")
        ref, cut = ctx.dir / "ref", ctx.dir / "cut"
        o = ctx.run(args(ctx, ref))
        if o.rc != 0:
            raise RuntimeError("uninterrupted run failed: " + o.out[-400:])
        a = args(ctx, cut) + ["--checkpoint-every", "200" if kind == "run" else "1"]
        if sig == signal.SIGKILL:
            res = cut / "cantilever-explicit" if kind == "run" else cut
            o = ctx.signalled(a, res / ".incomplete" / "checkpoint.h5", signal.SIGKILL, delay=0.5)
        else:
            o = ctx.run(a, env={"TMLAB_TEST_STOP_AFTER_PROGRESS": "1:" + signal.Signals(sig).name})
        return {"ref": ref, "cut": cut, "cut_rc": o.rc, "args": a}

    def command(ctx, s):
        return s["args"] + ["--resume"]

    def rule(ctx, s, o):
        c = crashed(o)
        if c:
            return c
        if s["cut_rc"] == 0:
            return WEAK, "not tried: the run finished before the signal"
        if o.rc != 0:
            return BAD, "resume failed (exit %s): %s" % (o.rc, o.first_line())
        name = {"fit": "fit.json", "discover": "report.json"}.get(kind)
        if name:
            a = without_times(json.loads((s["ref"] / name).read_text()))
            b = without_times(json.loads((s["cut"] / name).read_text()))
            if a != b:
                return WEAK, "resumed, but %s differs from the uninterrupted run's" % name
        elif not (s["cut"] / "cantilever-explicit" / "summary.json").exists():
            return BAD, "resumed without a complete result"
        return GOOD, "resumed (%s) to %s" % (signal.Signals(sig).name,
                                             "the uninterrupted result" if name else "a complete result")

    return setup, command, rule


def realtime_case(ctx, trajectory: dict, extra: Optional[dict] = None) -> Path:
    src = ctx.source / "cases" / "realtime" / "liver-poke.json"
    c = json.loads(strip_comments(src.read_text()))
    c["liver"]["mesh"] = str(ctx.source / "meshes" / "liver.msh")
    c["trajectory"] = trajectory
    c.update(extra or {})
    p = ctx.dir / "case" / "rt.json"
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps(c, indent=1))
    return p


# -- weak bullets: helpers --------------------------------------------------------------------------

def s_tiny(ctx, **kw):
    return {"csv": tiny(ctx.dir / "d", **kw)}


def s_csv_field(text_field: str):
    def setup(ctx):
        csv = tiny(ctx.dir / "d")
        lines = csv.read_bytes().split(b"\n")
        parts = lines[5].split(b",")
        parts[2] = text_field.encode("latin-1")
        lines[5] = b",".join(parts)
        csv.write_bytes(b"\n".join(lines))
        return {"csv": csv}

    return setup


def s_raw_phantom(edit: Callable[[List[str]], List[str]], same_folder: bool = False):
    def setup(ctx):
        d = ctx.dir / "raw"
        d.mkdir()
        lines = ctx.raw_phantom().read_text(errors="replace").splitlines()
        (d / "A1.csv").write_text("\n".join(edit(lines)) + "\n")
        s = {"raw": d / "A1.csv", "out": d if same_folder else ctx.dir / "out"}
        return protect(ctx, s, d / "A1.csv")

    return setup


def rig_args(ctx, *extra):
    return ["rig", "indentation", "--out", str(ctx.dir / "rig")] + list(extra)


def rig_refused(*words):
    def rule(ctx, s, o):
        v, note = refused(o, *words)
        left = list((ctx.dir / "rig").rglob("*")) if (ctx.dir / "rig").exists() else []
        if o.rc not in (0, None) and (ctx.dir / "rig").exists():
            return WEAK, "refused, but left %s behind" % ("files" if left else "an empty folder")
        return v, note

    return rule


def no_cleanup(ctx, s):
    return s


def bad_cases(add) -> None:
    """The 7 bad items of issue 26."""
    # ---- bad 1 ----
    add("B1-foreign-manifest-fit", "fit --out V, V holds someone's manifest.json and thesis.tex", s_foreign_fit,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "V"),
        lambda ctx, s, o: refused_keeping(o, s, "not a tmlab result directory", "V"), "bad 1")
    add("B1-foreign-manifest-run", "run --results R, R/<case>/ holds a foreign manifest.json", s_foreign_run,
        lambda ctx, s: run_args(ctx.dir / "res"),
        lambda ctx, s, o: refused_keeping(o, s, "not a tmlab result directory"), "bad 1")
    add("B1-foreign-no-manifest", "fit --out V, V holds only thesis.tex and data/",
        lambda ctx: (foreign_files(ctx.dir / "V", manifest=False),
                     protect(ctx, {"csv": tiny(ctx.dir / "d")}, ctx.dir / "V"))[1],
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "V"),
        lambda ctx, s, o: refused_keeping(o, s, "not a tmlab result directory"), "bad 1")
    add("B1-crafted-marker", ".tmlab-result listing ../victim.txt and an absolute path", s_crafted_marker,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "V"),
        lambda ctx, s, o: refused_keeping(o, s, ".tmlab-result"), "bad 1")
    add("B1-crafted-manifest", "manifest.json + summary.json listing ../victim.txt", s_crafted_manifest,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "V"),
        lambda ctx, s, o: refused_keeping(o, s, "not a tmlab result directory"), "bad 1")
    add("B1-user-file-in-result", "a previous fit's folder plus the user's my-notes.txt", s_previous_plus_user_file,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "V"),
        lambda ctx, s, o: refused_keeping(o, s, "my-notes.txt"), "bad 1")
    # ---- bad 2 ----
    add("B2-symlink-out", "fit --out LINK, LINK -> an empty folder", lambda ctx: s_symlink(ctx, False),
        lambda ctx, s: fit_args(s["csv"], s["link"]),
        lambda ctx, s, o: result_rule("target", symlink=True)(ctx, s, o), "bad 2")
    add("B2-symlink-other-fs", "fit --out LINK, LINK -> a folder on /dev/shm (tmpfs)", lambda ctx: s_symlink(ctx, True),
        lambda ctx, s: fit_args(s["csv"], s["link"]),
        lambda ctx, s, o: result_rule("target", symlink=True)(ctx, s, o), "bad 2")
    add("B2-symlink-run-result", "run --results R, R/cube-uniaxial -> a folder",
        lambda ctx: (lambda s: (ctx.dir.joinpath("res").mkdir(), s["link"].rename(ctx.dir / "res" / "cube-uniaxial"),
                                s.update(link=ctx.dir / "res" / "cube-uniaxial"), s)[-1])(s_symlink(ctx, False)),
        lambda ctx, s: run_args(ctx.dir / "res"),
        lambda ctx, s, o: result_rule("target", symlink=True)(ctx, s, o), "bad 2")
    # ---- bad 3 ----
    add("B3-fit-out-dot", "fit --out . in a folder of someone's files", s_cwd,
        lambda ctx, s: (lambda: ctx.run(fit_args(s["csv"], Path(".")), cwd=s["cwd"])),
        lambda ctx, s, o: refused_keeping(o, s, "a folder of its own"), "bad 3")
    add("B3-fit-out-empty", "fit --out \"\"", s_cwd,
        lambda ctx, s: (lambda: ctx.run(fit_args(s["csv"], Path("")) [:-1] + [""], cwd=s["cwd"])),
        lambda ctx, s, o: refused_keeping(o, s, "a folder of its own"), "bad 3")
    add("B3-discover-out-dot", "discover --out .", s_cwd,
        lambda ctx, s: (lambda: ctx.run(disc_args(s["csv"], Path(".")), cwd=s["cwd"])),
        lambda ctx, s, o: refused_keeping(o, s, "a folder of its own"), "bad 3")
    add("B3-fit-out-ancestor", "fit --out .. (the parent of the working folder)", s_cwd,
        lambda ctx, s: (lambda: ctx.run(fit_args(s["csv"], Path("..")), cwd=s["cwd"])),
        lambda ctx, s, o: refused_keeping(o, s, "a folder of its own"), "bad 3")
    add("B3-fit-out-home", "fit --out $HOME (a scratch HOME with files)",
        lambda ctx: (foreign_files(ctx.dir / "home"), protect(ctx, {"csv": tiny(ctx.dir / "d")}, ctx.dir / "home"))[1],
        lambda ctx, s: (lambda: ctx.run(fit_args(s["csv"], ctx.dir / "home"), env={"HOME": str(ctx.dir / "home")})),
        lambda ctx, s, o: refused_keeping(o, s, "a folder of its own"), "bad 3")
    add("B3-fit-out-root", "fit --out /", lambda ctx: {"csv": tiny(ctx.dir / "d"), "root": sorted(os.listdir("/"))},
        lambda ctx, s: fit_args(s["csv"], Path("/")),
        lambda ctx, s, o: (BAD, "/ changed") if sorted(os.listdir("/")) != s["root"] else refused(o, "a folder of its own"),
        "bad 3")
    # ---- bad 4 ----
    add("B4-convert-over-input", "data convert X.csv --out <X's own folder> (same stem)",
        s_raw_phantom(lambda l: l, same_folder=True), lambda ctx, s: ["data", "convert", s["raw"], "--out", s["out"]],
        lambda ctx, s, o: refused_keeping(o, s, "A1.csv"), "bad 4")
    # ---- bad 5 ----
    def s_phantom_negated(ctx):
        csv = ctx.copy_phantom("neg")
        lines = csv.read_text().splitlines()
        head = lines[0].split(",")
        k = head.index("force_N")
        out = [lines[0]]
        for l in lines[1:]:
            f = l.split(",")
            if f[k].startswith("-"):
                f[k] = f[k][1:]
            elif f[k].strip() not in ("0", "0.0"):
                f[k] = "-" + f[k].lstrip("+")
            out.append(",".join(f))
        csv.write_text("\n".join(out) + "\n")
        return {"csv": csv}

    def wrong_sign_rule(ctx, s, o):
        if find(ctx.dir, "RUNNING"):
            return BAD, "stale RUNNING" + (" after a crash" if crashed(o) else "")
        if o.rc == 0:
            return BAD, "silently wrong: a fit of wrong-sign data reported as complete"
        return refused(o, "sign")

    add("B5-fit-wrong-sign", "fit on the phantom with its force negated (the wrong sign convention)",
        s_phantom_negated, lambda ctx, s: ["fit", s["csv"], "--model", "neo_hookean", "--no-plots", "--quiet", "--out",
                                           ctx.dir / "out"], wrong_sign_rule, "bad 5")
    add("B5-fit-wrong-sign-no-profile", "the same with --no-profile", s_phantom_negated,
        lambda ctx, s: ["fit", s["csv"], "--model", "neo_hookean", "--no-profile", "--no-plots", "--quiet", "--out",
                        ctx.dir / "out"], wrong_sign_rule, "bad 5")
    add("B5-fit-wrong-sign-tiny", "fit on a tiny set whose force has the wrong sign", lambda ctx: s_tiny(ctx, sign=-1),
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out"), wrong_sign_rule, "bad 5")
    add("B5-discover-wrong-sign", "discover on the phantom with its force negated", s_phantom_negated,
        lambda ctx, s: disc_args(s["csv"], ctx.dir / "out", "--max-samples", "150"),
        lambda ctx, s, o: (BAD, "silently wrong: explained as an effect, exit 0")
        if o.rc == 0 else refused(o, "sign"), "bad 5")
    # ---- bad 6 ----
    for sig in (signal.SIGINT, signal.SIGTERM):
        add("B6-realtime-record-%s" % signal.Signals(sig).name, "realtime --record --duration 3600, then %s"
            % signal.Signals(sig).name, lambda ctx: {},
            (lambda sig: lambda ctx, s: (lambda: ctx.signalled(
                ["realtime", "liver-poke", "--record", "--duration", "3600", "--no-frames", "--results", ctx.dir / "res"],
                ctx.dir / "res" / "realtime" / "RUNNING", sig)))(sig),
            signal_rule(lambda ctx, s: ctx.dir / "res" / "realtime", sig), "bad 6")
    # ---- bad 7 ----
    add("B7-full-disk-fit", "fit --out on a full tmpfs (128 KiB, filled by someone's file)", lambda ctx: s_tiny(ctx),
        lambda ctx, s: (lambda: full_disk(ctx, lambda m: fit_args(s["csv"], m / "out"))),
        full_disk_rule(lambda ctx: ctx.dir / "disk" / "out"), "bad 7")
    add("B7-full-disk-run", "run --results on a full tmpfs", lambda ctx: {},
        lambda ctx, s: (lambda: full_disk(ctx, lambda m: run_args(m))),
        full_disk_rule(lambda ctx: ctx.dir / "disk" / "cube-uniaxial"), "bad 7")
    add("B7-full-disk-run-64k", "run --results on an empty 64 KiB tmpfs (runs out while writing HDF5)",
        lambda ctx: {}, lambda ctx, s: (lambda: full_disk(ctx, lambda m: run_args(m), 65536, fill=False)),
        full_disk_rule(lambda ctx: ctx.dir / "disk" / "cube-uniaxial"), "bad 7")
    add("B7-full-disk-hereditary", "hereditary --quick --results on a full tmpfs (HDF5 output)", lambda ctx: {},
        lambda ctx, s: (lambda: full_disk(ctx, lambda m: ["hereditary", "--quick", "--no-liver", "--histories",
                                                          "ramp_hold", "--no-plots", "--results", str(m)])),
        full_disk_rule(lambda ctx: ctx.dir / "disk" / "hereditary"), "bad 7")


def weak_cases(add) -> None:
    """The weak bullets of issue 26 on data, numbers, messages and fit, each as its own case."""
    def deep_json(ctx):
        csv = tiny(ctx.dir / "d")
        meta = json.loads(csv.with_suffix(".json").read_text())
        text = json.dumps(meta)[:-1] + ', "deep_1": ' + "[" * 100000 + "]" * 100000 + "}"
        csv.with_suffix(".json").write_text(text)
        return {"csv": csv}

    add("W-nested-json", "data show on a NAME.json nested 100000 deep", deep_json,
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: (WEAK, "took %.1f s" % o.seconds) if o.seconds > 10 else refused(o, "64"),
        "weak: nested JSON")
    add("W-long-name-data", "a 300-character name in NAME.json",
        lambda ctx: s_tiny(ctx, meta={"format": "tmlab-measured/1", "name": "a" * 300, "test": "unconfined_compression",
                                      "sample": {"shape": "cylinder", "radius_m": 0.025, "height_m": 0.03,
                                                 "bottom": "frictionless", "platens": "frictionless"}}),
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out"),
        # The length rule must come first and name its limit (the character rule did before).
        lambda ctx, s, o: refused(o, "300 characters long: at most") if o.rc != 0
        else (GOOD, "accepted (the name is a note)"),
        "weak: 300-character name")
    add("W-long-name-case", "run a case whose name has 300 characters",
        lambda ctx: {"case": (lambda p: (p.write_text(json.dumps(dict(json.loads(strip_comments(
            (ctx.source / "cases" / "cube-uniaxial.json").read_text())), name="a" * 300))), p)[1])(ctx.dir / "c.json")},
        lambda ctx, s: ["run", s["case"], "--no-plots", "--results", ctx.dir / "res"],
        lambda ctx, s, o: refused(o, "100 characters") if "1 to 100" not in o.out else refused(o),
        "weak: 300-character name")
    add("W-csv-plus-dot5", "a CSV field +.5", s_csv_field("+.5"),
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: refused(o, "+.5"), "weak: strict numbers")
    add("W-fix-hex", "--fix poisson=0x0.8p-1", s_tiny,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", "--fix", "poisson=0x0.8p-1"),
        lambda ctx, s, o: refused(o, "--fix"), "weak: strict numbers")
    for pid, port in (("hex", "0x4A3B"), ("blank", " 1.9e4")):
        add("W-port-" + pid, "realtime --serve --port %r" % port, lambda ctx: {},
            (lambda port: lambda ctx, s: ["realtime", "liver-poke", "--serve", "--port", port, "--duration", "1"])(port),
            lambda ctx, s, o: refused(o, "--port"), "weak: strict numbers")
    add("W-starts-hex", "fit --starts 0x10", s_tiny,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", starts="0x10"),
        lambda ctx, s, o: refused(o, "--starts"), "weak: strict numbers")
    add("W-nul-in-field", "a NUL byte in a CSV field", s_csv_field("12\x0034"),
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: (WEAK, "the message is cut at the NUL") if b"\x00" in o.raw or "34" not in o.out
        else refused(o), "weak: NUL / ANSI in messages")
    add("W-ansi-in-field", "ANSI escape codes in a CSV field", s_csv_field("\x1b[31mRED\x1b[0m"),
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: (WEAK, "ESC printed raw to the terminal") if b"\x1b" in o.raw else refused(o),
        "weak: NUL / ANSI in messages")
    add("W-show-directory", "data show on a directory", lambda ctx: {"p": (ctx.dir / "x.csv").mkdir() or ctx.dir / "x.csv"},
        lambda ctx, s: ["data", "show", s["p"], "--no-plots"],
        lambda ctx, s, o: (WEAK, "says no such file") if "no such file" in o.out.lower() else refused(o, "director"),
        "weak: directory / FIFO")
    add("W-show-fifo", "data show on a FIFO", lambda ctx: {"p": (os.mkfifo(ctx.dir / "f.csv"), ctx.dir / "f.csv")[1]},
        lambda ctx, s: (lambda: ctx.run(["data", "show", s["p"], "--no-plots"], timeout=30)),
        lambda ctx, s, o: (WEAK, "says no such file") if "no such file" in o.out.lower()
        else refused(o, "regular file"), "weak: directory / FIFO")
    add("W-convert-directory", "data convert on a directory", lambda ctx: {"p": (ctx.dir / "x.csv").mkdir() or ctx.dir / "x.csv"},
        lambda ctx, s: ["data", "convert", s["p"], "--out", ctx.dir / "out"],
        lambda ctx, s, o: (WEAK, "says no such file") if "no such file" in o.out.lower() else refused(o, "director"),
        "weak: directory / FIFO")
    add("W-convert-short-height", "convert: header height 1 mm, compression to 9 mm",
        s_raw_phantom(lambda l: [x.replace("Height: 30mm", "Height: 1mm") for x in l]),
        lambda ctx, s: ["data", "convert", s["raw"], "--out", s["out"]],
        lambda ctx, s, o: refused(o, "height"), "weak: convert checks")
    add("W-convert-one-row", "convert a file with one data row", s_raw_phantom(lambda l: l[:9]),
        lambda ctx, s: ["data", "convert", s["raw"], "--out", s["out"]],
        lambda ctx, s, o: refused(o), "weak: convert checks")

    def s_convert_over(ctx):
        s = s_raw_phantom(lambda l: l)(ctx)
        s["out"].mkdir()
        (s["out"] / "A1.csv").write_text("my own file\n")
        (s["out"] / "A1.json").write_text("{\"mine\": 1}\n")
        return protect(ctx, s, s["out"])

    add("W-convert-over-same-names", "convert into a folder holding A1.csv / A1.json of the user's", s_convert_over,
        lambda ctx, s: ["data", "convert", s["raw"], "--out", s["out"]],
        lambda ctx, s, o: (WEAK, "overwrote the user's same-named files silently")
        if lost(s["before"], snapshot(*s["roots"])) else refused(o, "A1"), "weak: convert overwrites")
    add("W-fix-conflicts-spec", "SPEC poisson=0.3 with --fix poisson=0.45", s_tiny,
        lambda ctx, s: ["fit", s["csv"], "--model", "neo_hookean,poisson=0.3", "--fix", "poisson=0.45", "--starts", "2",
                        "--no-profile", "--no-plots", "--quiet", "--out", ctx.dir / "out"],
        lambda ctx, s, o: refused(o, "poisson"), "weak: conflicting fixes")
    add("W-fix-twice", "--fix poisson=0.3 --fix poisson=0.45", s_tiny,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", "--fix", "poisson=0.3", "--fix", "poisson=0.45"),
        lambda ctx, s, o: refused(o, "poisson"), "weak: conflicting fixes")

    def local_runs_rule(ctx, s, o):
        c = crashed(o)
        if c:
            return c
        if o.rc != 0:
            return refused(o, "--local-runs")
        j = json.loads((ctx.dir / "out" / "fit.json").read_text())
        got = json.dumps(j)
        rec = j.get("global_stage", {}).get("local_runs", j.get("local_runs"))
        return (WEAK, "fit.json records local_runs %s although at most 12 ran" % rec) if '"local_runs": 100' in got \
            else (GOOD, "records %s" % rec)

    add("W-local-runs-100", "--local-runs 100 with --starts 12", s_tiny,
        lambda ctx, s: ["fit", s["csv"], "--model", "neo_hookean", "--starts", "12", "--local-runs", "100",
                        "--no-profile", "--no-plots", "--quiet", "--out", ctx.dir / "out"],
        local_runs_rule, "weak: --local-runs recorded")

    def s_finished_fit(ctx):
        csv = tiny(ctx.dir / "d")
        if ctx.run(fit_args(csv, ctx.dir / "out")).rc != 0:
            raise RuntimeError("setup fit failed")
        return {"csv": csv}

    add("W-resume-finished", "fit --resume on a finished fit", s_finished_fit,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", "--resume"),
        lambda ctx, s, o: (WEAK, "says: " + o.first_line()) if "stopped before writing one" in o.out
        else (BAD, "the complete fit was lost") if not (ctx.dir / "out" / "summary.json").exists()
        else refused(o, "nothing to resume", "complete") if o.rc != 0
        else (GOOD, "nothing to resume: " + o.first_line()),
        "weak: --resume on a finished fit")

    def discover_clean_rule(ctx, s, o):
        c = crashed(o)
        if c:
            return c
        if o.rc != 0:
            return WEAK, "exit %d: %s" % (o.rc, o.first_line())
        j = json.loads((ctx.dir / "out" / "report.json").read_text())
        added = [st.get("effect") for st in j.get("steps", []) if st.get("action") == "add" and st.get("accepted", True)]
        model = str(j.get("final", {}).get("model", ""))
        extra = [e for e in ("force_drift", "strain_dependent_relaxation") if e in model]
        return (WEAK, "adds %s to a noise-free ramp" % ", ".join(extra)) if extra else (GOOD, "final model " + model)

    add("W-discover-clean-ramp", "discover on one noise-free ramp", lambda ctx: s_tiny(ctx, ripple=False),
        lambda ctx, s: disc_args(s["csv"], ctx.dir / "out"), discover_clean_rule, "weak: discover on a clean ramp")


def weak_cases_rig_compare_realtime(add) -> None:
    """The weak bullets of issue 26 on rig, compare and realtime, each as its own case."""
    for rid, mat, word in (("E-negative", '{"E": -1, "nu": 0.45, "density": 1000}', "E"),
                           ("unknown-key", '{"E": 3000, "nu": 0.45, "density": 1000, "colour": 1}', "colour"),
                           ("ogden-alpha0", '{"law": "ogden", "mu": [3000], "alpha": [0], "nu": 0.45, "density": 1000}',
                            "alpha")):
        add("W-rig-material-" + rid, "rig --material %s" % mat, lambda ctx: {},
            (lambda mat: lambda ctx, s: rig_args(ctx, "--material", mat))(mat), rig_refused(word),
            "weak: rig checks")
    add("W-rig-huge-mesh", "rig indentation --cells 400 --layers 400 (memory limited to 2 GiB)", lambda ctx: {},
        lambda ctx, s: (lambda: ctx.run(rig_args(ctx, "--cells", "400", "--layers", "400"), timeout=300,
                                        limit_memory=2 << 30)),
        lambda ctx, s, o: (WEAK, "internal error: std::bad_alloc") if "bad_alloc" in o.out else rig_refused("memory")(ctx, s, o),
        "weak: rig checks")
    add("W-rig-steps-1e8", "rig --steps-per-segment 1e8", lambda ctx: {},
        lambda ctx, s: rig_args(ctx, "--steps-per-segment", "1e8"), rig_refused("--steps-per-segment"),
        "weak: rig checks")
    add("W-rig-at-nan", "rig --at nan,0", lambda ctx: {}, lambda ctx, s: rig_args(ctx, "--at", "nan,0"),
        rig_refused("--at"), "weak: rig checks")
    add("W-rig-at-edge", "rig --at 0.5,0.5 (outside the block)", lambda ctx: {},
        lambda ctx, s: rig_args(ctx, "--at", "0.5,0.5"),
        lambda ctx, s, o: (WEAK, "blames indenter_radius") if "--at" not in o.out and "indenter_radius" in o.out
        else rig_refused("--at")(ctx, s, o), "weak: rig checks")

    def compare_twice(ctx, s):
        def go():
            a = ctx.run(["compare", "cube-uniaxial", "--against", "tl_oracle", "--results", ctx.dir / "res"])
            s["first"] = a
            s["first_files"] = snapshot(ctx.dir / "res")
            return ctx.run(["compare", "cube-uniaxial", "--against", "reference", "--results", ctx.dir / "res"])
        return go

    def compare_rule(ctx, s, o):
        c = crashed(o) or crashed(s["first"])
        if c:
            return c
        if o.rc != 0 and "reference" in o.out and "not built" in o.out:
            return WEAK, "not tried: the deal.II reference is not built"
        dirs = sorted(p.name for p in (ctx.dir / "res").iterdir() if "compare" in p.name)
        if len(dirs) == 1:
            return WEAK, "both write %s/: the second replaced the first" % dirs[0]
        return GOOD, "separate folders: " + ", ".join(dirs)

    add("W-compare-same-folder", "compare --against tl_oracle, then --against reference", lambda ctx: {},
        compare_twice, compare_rule, "weak: compare folders")
    add("W-realtime-trajectory-escape", "a realtime trajectory file ../../../../etc/passwd",
        lambda ctx: {"case": realtime_case(ctx, {"type": "csv", "file": "../../../../../../../../etc/passwd"})},
        lambda ctx, s: ["realtime", s["case"], "--duration", "0.1"],
        lambda ctx, s, o: (WEAK, "echoes the file's content") if "root:" in o.out else refused(o, "passwd"),
        "weak: realtime trajectory path")
    add("W-realtime-results-without-record", "realtime --results D --no-frames without --record", lambda ctx: {},
        lambda ctx, s: ["realtime", "liver-poke", "--duration", "0.2", "--results", ctx.dir / "D", "--no-frames"],
        lambda ctx, s, o: (WEAK, "both options silently ignored") if o.rc == 0 else refused(o, "--record"),
        "weak: realtime options")
    add("W-platens-without-bottom", "compression data with sample.platens and no sample.bottom",
        lambda ctx: s_tiny(ctx, meta={"format": "tmlab-measured/1", "name": "tiny", "test": "unconfined_compression",
                                      "sample": {"shape": "cylinder", "radius_m": 0.025, "height_m": 0.03,
                                                 "platens": "frictionless"}}),
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: (GOOD, "accepted") if o.rc == 0 else (WEAK, "refused: " + o.first_line()),
        "weak: platens without bottom")


def good_and_property_cases(add) -> None:
    """The good behaviours issue 26 names (resume after SIGINT / SIGTERM / SIGKILL) and the
    result-directory property on fit, run and realtime."""
    for kind, sig in (("fit", signal.SIGINT), ("discover", signal.SIGTERM), ("run", signal.SIGKILL)):
        st, cm, ru = resume_case(kind, sig)
        add("G-resume-%s-%s" % (kind, signal.Signals(sig).name), "%s stopped by %s, then --resume"
            % (kind, signal.Signals(sig).name), st, cm, ru, "good: resume")
    # ---- the property, on fit and run ----
    add("P-previous-complete", "fit into its own previous complete result", s_previous_complete,
        lambda ctx, s: fit_args(s["csv"], s["out"]), result_rule("out"), "property")
    add("P-previous-interrupted", "fit (no --resume) into an interrupted result", s_previous_interrupted,
        lambda ctx, s: fit_args(s["csv"], s["out"]), result_rule("out"), "property")
    add("P-empty-folder", "fit --out an empty folder",
        lambda ctx: (ctx.dir.joinpath("V").mkdir(), {"csv": tiny(ctx.dir / "d"), "out": ctx.dir / "V"})[1],
        lambda ctx, s: fit_args(s["csv"], s["out"]), result_rule("out"), "property")
    def dot_rule(ctx, s, o):
        # --results names a root: ./cube-uniaxial/ is a folder of its own, so a complete result there
        # is right; a refusal naming the rule is right too.
        if o.rc != 0 and "a folder of its own" in o.out:
            return refused_keeping(o, s, "a folder of its own")
        return result_rule("res")(ctx, dict(s, res=s["cwd"] / "cube-uniaxial"), o)

    add("P-run-results-dot", "run --results . (results root: ./cube-uniaxial/)", s_cwd,
        lambda ctx, s: (lambda: ctx.run(run_args(Path(".")), cwd=s["cwd"])),
        dot_rule, "property")
    add("P-out-is-a-file", "fit --out an existing regular file",
        lambda ctx: (lambda f: (f.write_text("mine\n"), protect(ctx, {"csv": tiny(ctx.dir / "d"), "f": f}, f))[1])(
            ctx.dir / "file.txt"),
        lambda ctx, s: fit_args(s["csv"], s["f"]), lambda ctx, s, o: refused_keeping(o, s, "file.txt"), "property")

    def s_two_writers(ctx):
        s = {}
        log = open(ctx.dir / "first.log", "wb")
        s["first"] = subprocess.Popen([str(ctx.tmlab), "realtime", "liver-poke", "--record", "--duration", "3600",
                                       "--no-frames", "--results", str(ctx.dir / "res")], env=ctx.env(), stdout=log,
                                      stderr=subprocess.STDOUT, start_new_session=True)
        t0 = time.monotonic()
        while not (ctx.dir / "res" / "realtime" / "RUNNING").exists() and time.monotonic() - t0 < 300 \
                and s["first"].poll() is None:
            time.sleep(0.05)
        return s

    def two_writers_rule(ctx, s, o):
        os.killpg(s["first"].pid, signal.SIGKILL)
        s["first"].wait()
        return refused(o, "another tmlab run")

    add("P-second-writer", "a second realtime --record into a folder another one is writing", s_two_writers,
        lambda ctx, s: ["realtime", "liver-poke", "--record", "--duration", "0.2", "--no-frames", "--results",
                        ctx.dir / "res"], two_writers_rule, "property")

    def s_killed(ctx):
        o = ctx.signalled(["realtime", "liver-poke", "--record", "--duration", "3600", "--no-frames", "--results",
                           ctx.dir / "res"], ctx.dir / "res" / "realtime" / "RUNNING", signal.SIGKILL)
        return {}

    add("P-after-sigkill", "realtime --record after a SIGKILLed one (stale RUNNING)", s_killed,
        lambda ctx, s: ["realtime", "liver-poke", "--record", "--duration", "0.2", "--no-frames", "--results",
                        ctx.dir / "res"],
        lambda ctx, s, o: (GOOD, "stale marker reported, complete") if o.rc == 0 and "stale" in o.out and not complete(
            ctx.dir / "res" / "realtime") else result_rule("r")(ctx, {"r": ctx.dir / "res" / "realtime"}, o),
        "property")
    add("P-hostile-results-path", "run --results with quotes and $(...) in the path", lambda ctx: {},
        lambda ctx, s: run_args(ctx.dir / "r'$(touch X)';touch Y;'"),
        lambda ctx, s, o: (BAD, "a shell ran") if (ctx.dir / "X").exists() or (ctx.dir / "Y").exists() or Path("X").exists()
        else result_rule("r")(ctx, {"r": ctx.dir / "r'$(touch X)';touch Y;'" / "cube-uniaxial"}, o), "property")


def named_input_cases(add) -> None:
    """Plain bad input that must be refused naming the file, key or option."""
    add("N-fit-missing-file", "fit on a file that does not exist", lambda ctx: {},
        lambda ctx, s: fit_args(ctx.dir / "nope.csv", ctx.dir / "out"),
        lambda ctx, s, o: refused(o, "nope.csv"), "named input")
    add("N-fit-no-json", "fit on NAME.csv without NAME.json",
        lambda ctx: (lambda c: (c.with_suffix(".json").unlink(), {"csv": c})[1])(tiny(ctx.dir / "d")),
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out"), lambda ctx, s, o: refused(o, "tiny.json"), "named input")
    add("N-fit-unknown-law", "fit --model rubber", s_tiny,
        lambda ctx, s: ["fit", s["csv"], "--model", "rubber", "--out", ctx.dir / "out"],
        lambda ctx, s, o: refused(o, "rubber"), "named input")
    add("N-fit-starts-zero", "fit --starts 0", s_tiny,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", starts="0"),
        lambda ctx, s, o: refused(o, "--starts"), "named input")
    add("N-option-twice", "fit --starts 2 ... --starts 3 (the same option twice)", s_tiny,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", "--starts", "3"),
        lambda ctx, s, o: refused(o, "--starts"), "named input")
    add("N-fit-threads-text", "fit --threads many", s_tiny,
        lambda ctx, s: fit_args(s["csv"], ctx.dir / "out", "--threads", "many"),
        lambda ctx, s, o: refused(o, "--threads"), "named input")
    add("N-run-unknown-case", "run no-such-case", lambda ctx: {},
        lambda ctx, s: ["run", "no-such-case", "--results", ctx.dir / "res"],
        lambda ctx, s, o: refused(o, "no-such-case"), "named input")
    add("N-run-hostile-name", "a case named a';touch X;'", lambda ctx: {
        "case": (lambda p: (p.write_text(json.dumps(dict(json.loads(strip_comments(
            (ctx.source / "cases" / "cube-uniaxial.json").read_text())), name="a';touch X;'"))), p)[1])(ctx.dir / "c.json")},
        lambda ctx, s: ["run", s["case"], "--no-plots", "--results", ctx.dir / "res"],
        lambda ctx, s, o: (BAD, "a shell ran") if (ctx.dir / "X").exists() else refused(o, "name"), "named input")
    add("N-realtime-bad-coupling", "realtime --coupling magic", lambda ctx: {},
        lambda ctx, s: ["realtime", "liver-poke", "--coupling", "magic", "--duration", "0.1"],
        lambda ctx, s, o: refused(o, "magic"), "named input")
    add("N-realtime-negative-duration", "realtime --duration -1", lambda ctx: {},
        lambda ctx, s: ["realtime", "liver-poke", "--duration", "-1"],
        lambda ctx, s, o: refused(o, "--duration"), "named input")
    add("N-convert-no-out", "data convert without --out", lambda ctx: {},
        lambda ctx, s: ["data", "convert", ctx.raw_phantom()], lambda ctx, s, o: refused(o, "--out"), "named input")
    add("N-verify-unknown-case", "verify --case no-such-case", lambda ctx: {},
        lambda ctx, s: ["verify", "--case", "no-such-case", "--results", ctx.dir / "res"],
        lambda ctx, s, o: refused(o, "no-such-case"), "named input")
    add("N-csv-empty-file", "data show on an empty CSV",
        lambda ctx: (lambda c: (c.write_text(""), {"csv": c})[1])(tiny(ctx.dir / "d")),
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: refused(o, "tiny.csv"), "named input")
    add("N-csv-nan", "a CSV force nan", s_csv_field("nan"),
        lambda ctx, s: ["data", "show", s["csv"], "--no-plots", "--out", ctx.dir / "show"],
        lambda ctx, s, o: refused(o, "force_N"), "named input")
    add("N-mesh-info-missing", "mesh info on a missing file", lambda ctx: {},
        lambda ctx, s: ["mesh", "info", ctx.dir / "none.msh"], lambda ctx, s, o: refused(o, "none.msh"), "named input")


def make_cases() -> List[Case]:
    """The table: every case, in the order of the report."""
    cases: List[Case] = []

    def add(*a, **k):
        cases.append(Case(*a, **k))

    for section in (bad_cases, weak_cases, weak_cases_rig_compare_realtime, good_and_property_cases,
                    named_input_cases):
        section(add)
    return cases


# ---------------------------------------------------------------------------------------------------
# Running the table


def run_case(ctx: Ctx, case: Case) -> dict:
    ctx.dir = ctx.work / case.id
    shutil.rmtree(ctx.dir, ignore_errors=True)
    ctx.dir.mkdir(parents=True)
    t0 = time.monotonic()
    s: dict = {}
    try:
        s = case.setup(ctx) or {}
        cmd = case.command(ctx, s)
        o = cmd() if callable(cmd) else ctx.run(cmd)
        verdict, note = case.rule(ctx, s, o)
        if s.get("note"):
            note += " " + s["note"]
        outcome = "exit %s: %s" % (o.rc, note)
    except Exception as e:  # a case that could not be set up is reported, never fatal
        verdict, outcome = WEAK, "probe could not run the case: %s: %s" % (type(e).__name__, str(e)[-300:])
    finally:
        if s.get("cleanup"):
            shutil.rmtree(s["cleanup"], ignore_errors=True)
    return {"id": case.id, "case": case.tries, "issue": case.issue, "outcome": outcome, "verdict": verdict,
            "seconds": round(time.monotonic() - t0, 1)}


def full_disk_helper(argv: List[str]) -> int:
    """Inside the private mount namespace: mount the tmpfs, run the command, report its status."""
    mnt, size, fill, rest = argv[0], argv[1], argv[2] == "fill", argv[4:]
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=" + size, "tmpfs", mnt])
    if m.returncode != 0:
        print("cannot mount a tmpfs on " + mnt, flush=True)
        return 3
    # Someone's file fills the disk to two free pages: the quick results would fit in 128 KiB.
    st = os.statvfs(mnt)
    filler = b"x" * (max(0, st.f_bavail * st.f_frsize - 8192) if fill else 0)
    with open(os.path.join(mnt, "filler.bin"), "wb") as f:
        f.write(filler)
    p = subprocess.run(rest)
    state = {"files": [], "failed": {}, "filler_changed": False}
    for dirpath, dirnames, filenames in os.walk(mnt):
        for n in dirnames + filenames:
            full = os.path.join(dirpath, n)
            r = os.path.relpath(full, mnt)
            state["files"].append(r)
            if n == "FAILED":
                state["failed"][r] = open(full, errors="replace").read()[:2000]
    if os.path.exists(os.path.join(mnt, "filler.bin")):
        state["filler_changed"] = open(os.path.join(mnt, "filler.bin"), "rb").read() != filler
    with open(mnt.rstrip("/") + ".state.json", "w") as f:
        json.dump(state, f)
    subprocess.run(["umount", "-l", mnt])
    return p.returncode if p.returncode >= 0 else 128 - p.returncode


def md(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")[:160]


def main() -> int:
    if len(sys.argv) > 1 and sys.argv[1] == "--full-disk-helper":
        return full_disk_helper(sys.argv[2:])
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tmlab", required=True, type=Path, help="the tmlab binary (build/release/apps/tmlab/tmlab)")
    ap.add_argument("--out", required=True, type=Path, help="a folder for the probe's work and probe.json")
    ap.add_argument("--source", type=Path, default=Path(__file__).resolve().parents[2], help="the tmlab source tree")
    ap.add_argument("--only", default="", help="comma-separated case ids (prefixes) to run")
    a = ap.parse_args()
    tmlab = a.tmlab.resolve()
    out = a.out.resolve()
    work = out / "work"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    ctx = Ctx(tmlab, a.source.resolve(), work)
    cases = make_cases()
    if a.only:
        wanted = [w for w in a.only.split(",") if w]
        cases = [c for c in cases if any(c.id.startswith(w) for w in wanted)]
    rows = []
    print("| id | case | outcome | verdict |\n|---|---|---|---|", flush=True)
    for c in cases:
        r = run_case(ctx, c)
        rows.append(r)
        print("| %s | %s | %s | %s |" % (r["id"], md(r["case"]), md(r["outcome"]), r["verdict"]), flush=True)
    counts = {v: sum(1 for r in rows if r["verdict"] == v) for v in (GOOD, WEAK, BAD)}
    print("\n%d cases: %d good, %d weak, %d bad" % (len(rows), counts[GOOD], counts[WEAK], counts[BAD]))
    (out / "probe.json").write_text(json.dumps({"tmlab": str(tmlab), "counts": counts, "cases": rows}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
