#!/usr/bin/python3
"""Compare two tmlab result trees number for number (the bit-for-bit check of a refactoring).

usage: compare_results.py OLD_DIR NEW_DIR [--map OLD=NEW ...] [--root OLD=NEW ...]

--map renames parts of file paths (a renamed result); --root replaces OLD by NEW in every string of
the old tree before comparing (two checkouts in different folders). Needs h5py: run it with
Debian's /usr/bin/python3 (python3-h5py).

Walks OLD_DIR; for every file it finds the file of the same relative path under NEW_DIR (after the
--map renames of path parts) and compares:
  *.json  parsed, every value exactly (floats bit for bit), keys that are clock or build fields
          skipped (CLOCK_KEYS); missing and extra keys reported
  *.h5    every dataset's shape, dtype and bytes, every attribute (h5py)
  *.csv, *.md, *.txt, *.xdmf, *.vtu, *.pvd, *.html, *.log-free text: lines compared after dropping
          the ones that carry a clock (a word of CLOCK_WORDS)
  *.png and the protocol's own files (.tmlab-result, manifest.json) are listed, not compared
Prints each difference (path, key or dataset, old, new) and a total; exit 1 when any differ.
"""
import json, os, sys, re

CLOCK_KEYS = {"wall_seconds", "cpu_seconds", "seconds", "wall_s", "cpu_s", "elapsed_s", "time_s",
              "started", "finished", "start_time", "end_time", "date", "timestamp", "git_sha",
              "git_dirty", "build", "compiler", "host", "hostname", "run_id", "command_line",
              "wall_time_s", "solve_seconds", "duration_s", "elapsed", "wall", "cpu", "runtime_s",
              "wall_clock_s", "assembly_seconds", "total_seconds", "created", "version"}
CLOCK_WORDS = re.compile(r"(^Command:|wall|cpu|seconds|elapsed|[0-9] s\b|UTC|T[0-9]{2}:[0-9]{2}|git|sha|date|time)", re.I)
SKIP_FILES = {".tmlab-result", "manifest.json", "plots.log"}
ROOTS = []


def is_clock_key(k):
    k = str(k).lower()
    return k in CLOCK_KEYS or k.endswith("_seconds") or k.endswith("wall_s") or k.endswith("cpu_s") \
        or k.startswith("wall") or k.startswith("cpu_") or "timing" in k or k.endswith("_utc")


def cmp_json(a, b, where, out):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in a:
            if is_clock_key(k):
                continue
            if k not in b:
                out.append(f"{where}.{k}: missing in new")
            else:
                cmp_json(a[k], b[k], f"{where}.{k}", out)
        for k in b:
            if k not in a and not is_clock_key(k):
                out.append(f"{where}.{k}: extra in new")
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{where}: length {len(a)} -> {len(b)}")
        for i, (x, y) in enumerate(zip(a, b)):
            cmp_json(x, y, f"{where}[{i}]", out)
    else:
        if isinstance(a, str):
            for o, n in ROOTS:
                a = a.replace(o, n)
        if type(a) != type(b) or a != b:
            if isinstance(a, float) and isinstance(b, float) and a != a and b != b:
                return
            out.append(f"{where}: {a!r} -> {b!r}")


def cmp_h5(pa, pb, out):
    import h5py, numpy as np
    with h5py.File(pa, "r") as fa, h5py.File(pb, "r") as fb:
        names_a, names_b = [], []
        fa.visit(names_a.append)
        fb.visit(names_b.append)
        for n in names_a:
            nb = root_fix(n)  # --root renames apply to object names too
            if nb not in fb:
                out.append(f"{n}: missing in new")
                continue
            oa, ob = fa[n], fb[nb]
            if isinstance(oa, h5py.Dataset):
                if is_clock_key(n.split("/")[-1]):
                    continue
                if oa.shape != ob.shape or oa.dtype != ob.dtype:
                    out.append(f"{n}: shape/dtype {oa.shape} {oa.dtype} -> {ob.shape} {ob.dtype}")
                    continue
                va, vb = oa[()], ob[()]
                if isinstance(va, np.ndarray):
                    if va.tobytes() != vb.tobytes():
                        d = np.flatnonzero(va.reshape(-1) != vb.reshape(-1)) if va.dtype.kind in "fiu" else []
                        out.append(f"{n}: {len(d)} of {va.size} values differ")
                elif va != vb:
                    out.append(f"{n}: {va!r} -> {vb!r}")
            for k in oa.attrs:
                if is_clock_key(k):
                    continue
                if k not in ob.attrs:
                    out.append(f"{n}@{k}: attribute missing in new")
                elif root_fix(repr(oa.attrs[k])) != repr(ob.attrs[k]):
                    out.append(f"{n}@{k}: {oa.attrs[k]!r} -> {ob.attrs[k]!r}")
        renamed = {root_fix(n) for n in names_a}
        for n in names_b:
            if n not in renamed:
                out.append(f"{n}: extra in new")


def root_fix(s):
    for o, n in ROOTS:
        s = s.replace(o, n)
    return s


CLOCK_COLUMN = re.compile(r"(wall|cpu|seconds|time|\bms\b|\bs\b|speed|cost|per s|/s\b|overhead)", re.I)


def drop_clock_columns(lines):
    """Markdown tables: blank the cells of columns whose header names a clock (their values are times)."""
    out, clock_cols = [], None
    for i, l in enumerate(lines):
        if l.startswith("|"):
            cells = l.split("|")
            if clock_cols is None:  # a header row
                clock_cols = {j for j, c in enumerate(cells) if CLOCK_COLUMN.search(c)}
            else:
                cells = ["*" if j in clock_cols else c for j, c in enumerate(cells)]
            out.append("|".join(cells))
        else:
            clock_cols = None
            out.append(l)
    return out


def text_lines(path, fix):
    lines = open(path, errors="replace").read().splitlines()
    if path.endswith(".md"):
        lines = drop_clock_columns(lines)
    return [fix(l) for l in lines if not CLOCK_WORDS.search(l) or l.startswith("|")]


def cmp_text(pa, pb, out):
    la = text_lines(pa, root_fix)
    lb = text_lines(pb, lambda l: l)
    if la != lb:
        for i, (x, y) in enumerate(zip(la, lb)):
            if x != y:
                out.append(f"line {i + 1}: {x[:120]!r} -> {y[:120]!r}")
                break
        if len(la) != len(lb):
            out.append(f"{len(la)} -> {len(lb)} lines (clock lines dropped)")


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    maps = []
    argv = sys.argv[1:]
    for i, a in enumerate(argv):
        if a == "--map":
            old, new = argv[i + 1].split("=", 1)
            maps.append((old, new))
            args.remove(argv[i + 1])
        if a == "--root":
            old, new = argv[i + 1].split("=", 1)
            ROOTS.append((old, new))
            args.remove(argv[i + 1])
    quiet = "--quiet" in argv
    old_root, new_root = args[0], args[1]
    n_files = n_diff = 0
    skipped = []
    for dirpath, _, files in os.walk(old_root):
        for f in sorted(files):
            pa = os.path.join(dirpath, f)
            rel = os.path.relpath(pa, old_root)
            rel_new = rel
            for o, n in maps:
                rel_new = rel_new.replace(o, n)
            pb = os.path.join(new_root, rel_new)
            if f in SKIP_FILES or f.endswith(".png") or f.endswith(".pdf"):
                skipped.append(rel)
                continue
            n_files += 1
            out = []
            if not os.path.exists(pb):
                out.append("missing in new")
            elif f.endswith(".json"):
                try:
                    cmp_json(json.load(open(pa)), json.load(open(pb)), "", out)
                except json.JSONDecodeError as e:
                    out.append(f"unreadable JSON: {e}")
            elif f.endswith(".h5"):
                cmp_h5(pa, pb, out)
            else:
                cmp_text(pa, pb, out)
            if out:
                n_diff += 1
                print(f"DIFF {rel}:")
                for o in out[:20]:
                    print("   ", o)
                if len(out) > 20:
                    print(f"    ... {len(out) - 20} more")
    for dirpath, _, files in os.walk(new_root):
        for f in files:
            rel = os.path.relpath(os.path.join(dirpath, f), new_root)
            back = rel
            for o, n in maps:
                back = back.replace(n, o)
            if not os.path.exists(os.path.join(old_root, back)) and f not in SKIP_FILES and not f.endswith(".png"):
                print(f"EXTRA in new: {rel}")
    print(f"{n_files} files compared, {n_diff} differ; {len(skipped)} not compared (PNG, marker, manifest)")
    return 1 if n_diff else 0


if __name__ == "__main__":
    sys.exit(main())
