#!/usr/bin/env python3
"""docs/architecture.md's module table against the CMake link lists (ctest architecture_table).

usage: check_architecture_table.py ARCHITECTURE_MD MODULE_GRAPH_JSON

MODULE_GRAPH_JSON is written at configure time by tmlab_export_module_graph
(cmake/TmlabModuleGraph.cmake): every tmlab_* library with LINK_LIBRARIES ("link") and
INTERFACE_LINK_LIBRARIES ("interface"). Every row of the table "Modules (CMake targets)" whose
target is `tmlab::NAME` must list in its "depends on" cell exactly what tmlab_NAME links directly:
    public items, then "(privately a, b)" for the PRIVATE ones,
tmlab modules by their short name, external libraries by the names in EXTERNAL below. Other
parenthesised remarks and version numbers are ignored ("HDF5 (OpenMPI flavour)", "deal.II 9.4");
an item remarked "(when built)" may be absent. Every tmlab_* library that is not an external
wrapper must have a row. Exit 1 naming each wrong row and the difference.
"""
import json
import re
import sys

# link item -> the name the table uses; None: not listed (compile options every module gets).
EXTERNAL = {
    "tmlab::options": None,
    "Eigen3::Eigen": "Eigen",
    "nlohmann_json::nlohmann_json": "nlohmann-json",
    "GSL::gsl": "GSL",
    "tmlab::hdf5": "HDF5",
    "tmlab::cholmod": "CHOLMOD",
    "tmlab_dealii": "deal.II",
    "tmlab::dealii": "deal.II",
    "GTest::gtest": "GoogleTest",
    "benchmark::benchmark": "Google Benchmark",
    "Threads::Threads": "threads",
    "ZLIB::ZLIB": "zlib",
    "Boost::headers": "Boost",
}
WRAPPERS = {"tmlab_options", "tmlab_hdf5", "tmlab_cholmod", "tmlab_dealii"}  # external libraries


def item_name(item):
    """The table's name of one link item."""
    m = re.fullmatch(r"\$<LINK_ONLY:(.*)>", item)
    if m:
        item = m.group(1)
    if item in EXTERNAL:
        return EXTERNAL[item]
    if item.startswith("SUNDIALS::"):
        return "SUNDIALS"
    m = re.fullmatch(r"tmlab(?:::|_)(\w+)", item)
    if m:
        return m.group(1)
    return item


def cmake_deps(entry):
    """(public, private) name sets of one target of the module graph."""
    public = {item_name(i) for i in entry["interface"] if not i.startswith("$<LINK_ONLY:")}
    linked = {item_name(i) for i in entry["link"]}
    public.discard(None)
    linked.discard(None)
    return public, linked - public


def split_items(text):
    """Comma-separated items, commas inside parentheses kept."""
    items, depth, cur = [], 0, ""
    for ch in text:
        depth += ch == "("
        depth -= ch == ")"
        if ch == "," and depth == 0:
            items.append(cur)
            cur = ""
        else:
            cur += ch
    items.append(cur)
    return [i.strip() for i in items if i.strip()]


def parse_item(item):
    """(name, optional) of one table item: remarks in parentheses and version numbers dropped."""
    optional = "when built" in item
    name = re.sub(r"\([^)]*\)", "", item).replace("`", "").strip()
    name = re.sub(r"\s+[0-9][0-9.]*$", "", name).strip()
    if name.startswith("tmlab::"):
        name = name[len("tmlab::"):]
    return name, optional


def table_deps(cell):
    """(public, private, optional) name sets of one "depends on" cell."""
    private_text = ""
    start = cell.find("(privately ")
    if start >= 0:  # to its closing parenthesis, remarks inside kept
        depth, end = 0, start
        for end in range(start, len(cell)):
            depth += cell[end] == "("
            depth -= cell[end] == ")"
            if depth == 0:
                break
        private_text = cell[start + len("(privately "): end]
        cell = cell[:start] + cell[end + 1:]
    public, private, optional = set(), set(), set()
    for text, into in ((cell, public), (private_text, private)):
        for item in split_items(text):
            name, opt = parse_item(item)
            into.add(name)
            if opt:
                optional.add(name)
    return public, private, optional


def table_rows(markdown):
    """{target: (line number, depends-on cell)} of the module table."""
    lines = markdown.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("## Modules (CMake targets)"))
    rows = {}
    for n, line in enumerate(lines[start + 1:], start + 2):
        if line.startswith("## "):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 4:
            continue
        m = re.fullmatch(r"`tmlab::(\w+)`", cells[0])
        if m:
            rows["tmlab_" + m.group(1)] = (n, cells[2])
    return rows


def fmt(names):
    return ", ".join(sorted(names)) if names else "nothing"


def check(markdown, graph, where="docs/architecture.md"):
    """The list of errors (empty: the table matches)."""
    errors = []
    rows = table_rows(markdown)
    for target, (line, cell) in sorted(rows.items()):
        row = f"{where}:{line}: row `{target.replace('tmlab_', 'tmlab::', 1)}`"
        t_public, t_private, optional = table_deps(cell)
        if target not in graph:
            if "deal.II" not in t_public | t_private:  # the reference is built only with deal.II
                errors.append(f"{row}: no such CMake target")
            continue
        c_public, c_private = cmake_deps(graph[target])
        diffs = []
        for label, table, actual in (("public", t_public, c_public), ("private", t_private, c_private)):
            missing = actual - table
            extra = table - actual - optional
            if missing:
                diffs.append(f"{label}: CMake links {fmt(missing)}, the table does not say so")
            if extra:
                diffs.append(f"{label}: the table says {fmt(extra)}, CMake does not link it")
        if diffs:
            want = fmt(c_public) + (f" (privately {fmt(c_private)})" if c_private else "")
            errors.append(f"{row}: " + "; ".join(diffs) + f"; the link lists say: {want}")
    for target in sorted(set(graph) - set(rows) - WRAPPERS):
        errors.append(f"{where}: CMake target {target} has no row in the module table")
    return errors


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1], encoding="utf-8") as f:
        markdown = f.read()
    with open(argv[2], encoding="utf-8") as f:
        graph = json.load(f)
    errors = check(markdown, graph, argv[1])
    for e in errors:
        print(e, file=sys.stderr)
    if errors:
        print(f"{len(errors)} row(s) of the module table differ from the CMake link lists", file=sys.stderr)
        return 1
    print(f"module table matches the link lists of {len(graph)} tmlab_* libraries")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
