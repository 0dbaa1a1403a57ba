"""The tables of eval/experiments.toml's experiments, made from their kept CSVs, and the READMEs they live in.
tools/reproduce.py runs the commands; everything here is pure: it reads files and returns text, so
`tools/reproduce.py --check` can recompute every table without rendering anything. How a cell is declared:
tools/reproduce_declarations.py.

A kept CSV (eval/results/<name>.csv) starts with one comment line, the run's facts (date, commit, cores), then:
  eval:  run,method,spec,frame,<the metrics the tables read>   one row per run, method and frame (metrics.csv)
  bench: run,scene,metric,value                                rtdr bench --csv, the filter stage's metrics
                                                               prefixed by their back end (cpu_ms_temporal)
  ctest: claim,value,threshold                                 the stability suite's `stability:` lines
"""
import ast
import csv
import io
import math
import operator
import os
import re

from reproduce_declarations import SELECTORS, DeclarationError, frame_range

MARKER = re.compile(r"^<!-- experiment: ([\w-]+) -->$")
END_MARKER = "<!-- /experiment -->"
PENDING = re.compile(r"^Last hand-typed values \(measured [^)]+\), pending a run: `(?P<command>[^`]+)`\.$")


# ---- Kept CSVs ---------------------------------------------------------------------------------------------

def write_kept(experiment, facts, header, rows):
    """Writes the kept CSV atomically: the facts line, then the rows."""
    text = io.StringIO()
    text.write("# " + "; ".join(f"{k}={v}" for k, v in facts.items()) + "\n")
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    os.makedirs(os.path.dirname(experiment.results), exist_ok=True)
    partial = experiment.results + ".part"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(text.getvalue())
    os.replace(partial, experiment.results)


def read_kept(experiment):
    """(facts, header, rows) of the kept CSV, or None where the experiment has none (pending)."""
    if not os.path.exists(experiment.results):
        return None
    with open(experiment.results, encoding="utf-8") as f:
        first = f.readline()
        if not first.startswith("# "):
            raise DeclarationError(f"{experiment.results}: the first line must be the run's facts")
        facts = dict(item.split("=", 1) for item in first[2:].strip().split("; "))
        reader = csv.reader(f)
        header = next(reader, [])
        rows = list(reader)
    return facts, header, rows


def expected_header(experiment):
    if experiment.tool == "eval":
        return ["run", "method", "spec", "frame"] + experiment.metrics()
    if experiment.tool == "bench":
        return ["run", "scene", "metric", "value"]
    return ["claim", "value", "threshold"]


def records(experiment, header, rows):
    """The kept CSV as records {selector: name, metric: value}; raises where it is not what the declaration
    makes (other columns, a run, method or frame missing or extra, a spec that changed)."""
    where = experiment.results
    if header != expected_header(experiment):
        raise DeclarationError(f"{where}: columns {','.join(header)}; the declaration makes "
                               f"{','.join(expected_header(experiment))}")
    if any(len(r) != len(header) for r in rows):
        raise DeclarationError(f"{where}: a row has not {len(header)} values")
    if experiment.tool == "ctest":
        return [dict(zip(header, r)) for r in rows]
    if experiment.tool == "eval":
        wanted = [(run["id"], alias, spec, str(frame)) for run in experiment.runs
                  for alias, spec in experiment.methods.items()
                  for frame in range(frame_range(run["frames"])[0], frame_range(run["frames"])[1] + 1)]
        have = [tuple(r[:4]) for r in rows]
        if have != wanted:
            missing = sorted(set(wanted) - set(have))
            raise DeclarationError(f"{where}: its rows are not the declared runs x methods x frames, in order"
                                   + (f" (first missing: {','.join(missing[0])})" if missing else ""))
        out = []
        for r in rows:
            record = {"run": r[0], "method": r[1], "frame": int(r[3])}
            record.update({m: number(v) for m, v in zip(header[4:], r[4:])})
            scene = next(run.get("scene") for run in experiment.runs if run["id"] == r[0])
            record["scene"] = scene
            out.append(record)
        return out
    by_key = {}
    for run, scene, metric, value in rows:
        by_key.setdefault((run, scene), {"run": run, "scene": scene})[metric] = number(value)
    if sorted({run for run, _ in by_key}) != sorted(experiment.run_ids()):
        raise DeclarationError(f"{where}: its runs are not the declared ones ({', '.join(experiment.run_ids())})")
    return list(by_key.values())


def number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


# ---- Tables ------------------------------------------------------------------------------------------------

OPERATORS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv}


def evaluate(node, values):
    if isinstance(node, ast.Constant):
        return float(node.value)
    if isinstance(node, ast.Name):
        return values[node.id]
    if isinstance(node, ast.UnaryOp):
        v = evaluate(node.operand, values)
        return -v if isinstance(node.op, ast.USub) else v
    left, right = evaluate(node.left, values), evaluate(node.right, values)
    if isinstance(node.op, ast.Div) and right == 0.0:
        return math.nan
    return OPERATORS[type(node.op)](left, right)


def mean_of(table, recs, row, metric, chosen):
    """The mean of `metric` over the records the row (with `chosen` overriding its selectors) picks."""
    selection = {k: row[k] for k in SELECTORS if k in row}
    selection.update(chosen)
    frames = selection.pop("frames", None) or row.get("mean_over", table.mean_over)
    first, last = frame_range(frames) if frames else (-1, 1 << 30)
    picked = [r for r in recs if all(r.get(k) == v for k, v in selection.items())
              and first <= r.get("frame", first) <= last]
    if not picked:
        raise DeclarationError(f"table {table.marker}: no rows of {table.experiment.results} for "
                               + ", ".join(f"{k} {v}" for k, v in selection.items()))
    values = [r[metric] for r in picked if metric in r and not math.isnan(r[metric])]
    return sum(values) / len(values) if values else math.nan


def text_field(table, row, field):
    name, _, fmt = field.partition(":")
    if name in table.literal_keys:
        if name not in row:
            raise DeclarationError(f"table {table.marker}: a row has no '{name}'")
        value = row[name]
    else:
        run = next(r for r in table.experiment.runs if r["id"] == row.get("run", table.experiment.runs[0]["id"]))
        if name == "frames":
            value = run["frames"]
        elif name == "scene":
            value = row.get("scene") or run.get("scene", "")
        elif "method" not in row:
            raise DeclarationError(f"table {table.marker}: {{spec}} in a row that selects no method")
        else:
            value = table.experiment.methods[row["method"]]
    return format(value, fmt) if fmt else str(value)


def cell(table, recs, row, template):
    """(text, the first field's value) of one cell; a field without a value makes the whole cell "-"."""
    first_value = None

    def field(match):
        nonlocal first_value
        text = table.expand(match.group(1), row)
        if table.is_text(text):
            return text_field(table, row, text)
        tree, terms, fmt = table.parse_expression(text)
        values = {f"t{k}": mean_of(table, recs, row, metric, chosen) for k, (metric, chosen) in enumerate(terms)}
        value = evaluate(tree.body, values)
        if first_value is None:
            first_value = value
        if math.isnan(value) or math.isinf(value):
            raise ValueError("no value")
        return format(value, fmt)

    try:
        text = re.sub(r"\{([^{}]+)\}", field, template)
        return text or "-", first_value
    except ValueError:
        return "-", math.nan


def table_lines(table, recs):
    """The markdown table's lines, made from the records."""
    rows = table.rows
    if table.each_row:
        rows = [r for r in recs if not table.where or any(r["claim"].startswith(w) for w in table.where)]
        if not rows:
            raise DeclarationError(f"table {table.marker}: no line of {table.experiment.results} matches "
                                   + ", ".join(table.where))
    cells = [[("-", None) if c["head"] in row.get("omit", []) else cell(table, recs, row, c["cell"])
              for c in table.columns] for row in rows]
    for k, c in enumerate(table.columns):  # the best value of a column in bold
        if c.get("best"):
            values = [line[k][1] for line in cells if line[k][1] is not None and not math.isnan(line[k][1])]
            if values:
                best = min(values) if c["best"] == "min" else max(values)
                for line in cells:
                    if line[k][1] == best:
                        line[k] = (f"**{line[k][0]}**", best)
    return table.header() + ["| " + " | ".join(text for text, _ in line) + " |" for line in cells]


def footer(experiment, facts):
    """Under the table: the command, (a GPU's name,) the date, the commit, the cores (and the load at the start)."""
    device = f" on {facts['device']}" if facts.get("device") else ""
    load = f" (load average {facts['load']})" if facts.get("load") else ""
    return (f"Made by `{experiment.footer_command()}`{device}, {facts['date']}, commit {facts['commit']}, "
            f"{facts['cores']} cores{load}.")


def block(table, facts, recs):
    """The lines between a table's markers: the commands, the table, the footer."""
    lines = []
    if table.show_commands:
        lines += ["```sh"] + table.experiment.commands() + ["```", ""]
    return lines + table_lines(table, recs) + ["", footer(table.experiment, facts)]


# ---- READMEs -----------------------------------------------------------------------------------------------

def find_blocks(text):
    """{marker: (first line inside, line of the end marker)} of a markdown text; raises on unbalanced markers."""
    lines = text.split("\n")
    found, open_at, name = {}, None, None
    for k, line in enumerate(lines):
        match = MARKER.match(line)
        if match:
            if open_at is not None:
                raise DeclarationError(f"marker {name} is not closed before {match.group(1)} opens")
            open_at, name = k + 1, match.group(1)
            if name in found:
                raise DeclarationError(f"marker {name} appears twice")
        elif line == END_MARKER:
            if open_at is None:
                raise DeclarationError(f"line {k + 1}: {END_MARKER} without an opening marker")
            found[name] = (open_at, k)
            open_at = None
    if open_at is not None:
        raise DeclarationError(f"marker {name} is not closed")
    return found


def replace_block(path, marker, new_lines):
    """Rewrites the lines between a marker pair of a markdown file in place (atomically)."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    blocks = find_blocks(text)
    if marker not in blocks:
        raise DeclarationError(f"{path} has no <!-- experiment: {marker} --> ... {END_MARKER}")
    start, end = blocks[marker]
    lines = text.split("\n")
    lines[start:end] = new_lines
    partial = path + ".part"
    with open(partial, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    os.replace(partial, path)


def block_in(path, marker):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    blocks = find_blocks(text)
    if marker not in blocks:
        return None
    start, end = blocks[marker]
    return text.split("\n")[start:end]
