"""The experiments of eval/experiments.toml as data: their declarations, their kept CSVs, and the tables and
README blocks those make. tools/reproduce.py runs the commands; everything here is pure: it reads files and
returns text, so `tools/reproduce.py --check` can recompute every table without rendering anything.

A kept CSV (eval/results/<name>.csv) starts with one comment line, the run's facts (date, commit, cores), then:
  eval:  run,method,spec,frame,<the metrics the tables read>   one row per run, method and frame (metrics.csv)
  bench: run,scene,metric,value                                rtdr bench --csv, the filter stage's metrics
                                                               prefixed by their back end (cpu_ms_temporal)
  ctest: claim,value,threshold                                 the stability suite's `stability:` lines

A table cell is a template: text with fields in braces. `{label}` is the row's own text (any key of the row
but its selectors), or `{frames}`, `{scene}`, `{spec}`: its run's frames and scene, its method's spec.
`{rmse:.4f}` is a metric, the mean over the row's records (NaN and empty values skipped): `{rmse@asvgf}`
selects the method, run or scene named after the @ instead of the row's, `{rmse@40}` frame 40 and
`{rmse@51_60}` frames 51-60 instead of the row's `mean_over`. A field may be arithmetic on
metrics and numbers, `{rmse@asvgf / rmse@svgf - 1:+.0%}`. A cell with a field that has no value is "-".
"""
import ast
import csv
import io
import math
import operator
import os
import re
import tomllib

MARKER = re.compile(r"^<!-- experiment: ([\w-]+) -->$")
END_MARKER = "<!-- /experiment -->"
TOOLS = ("eval", "bench", "ctest")
SELECTORS = ("run", "method", "scene")  # the row keys that choose records rather than print text
BUILTINS = ("frames", "scene", "spec")   # the row fields that come from the run or the method
PENDING = re.compile(r"^Last hand-typed values \(measured [^)]+\), pending a run: `(?P<command>[^`]+)`\.$")


class DeclarationError(Exception):
    pass


# ---- Declarations ------------------------------------------------------------------------------------------

def frame_range(text):
    """"0-23" -> (0, 23)."""
    match = re.fullmatch(r"(\d+)-(\d+)", text)
    if not match or int(match.group(1)) > int(match.group(2)):
        raise DeclarationError(f"'{text}' is not a frame range A-B")
    return int(match.group(1)), int(match.group(2))


def only_keys(where, table, allowed):
    unknown = set(table) - set(allowed)
    if unknown:
        raise DeclarationError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}")


class Experiment:
    """One [[experiment]] of the declaration: its commands and its tables."""

    def __init__(self, d, results_dir):
        only_keys("experiment", d, ["name", "tool", "about", "size", "ref_spp", "flags", "methods", "run", "table",
                                    "device_step", "seconds"])
        self.name = d["name"]
        if not re.fullmatch(r"[a-z0-9][\w-]*", self.name):
            raise DeclarationError(f"experiment name '{self.name}': lower-case letters, digits, - and _")
        where = f"experiment {self.name}"
        self.tool = d.get("tool")
        if self.tool not in TOOLS:
            raise DeclarationError(f"{where}: tool must be one of {', '.join(TOOLS)}")
        self.about = d.get("about", "")
        self.size = d.get("size")
        self.ref_spp = d.get("ref_spp")
        self.flags = list(d.get("flags", []))
        self.methods = dict(d.get("methods", {}))  # alias -> spec, in the declared order
        self.device_step = d.get("device_step")  # a GPU experiment: run by tools/gpu_device.sh STEP
        self.seconds = d.get("seconds")          # bench and ctest: the measured wall time of a run here
        self.runs = []
        for r in d.get("run", []):
            only_keys(f"{where}, run", r, ["id", "scene", "frames", "args", "env", "device_csv"])
            if not re.fullmatch(r"\w+", r.get("id", "")):
                raise DeclarationError(f"{where}: every run needs an id of letters, digits and _")
            self.runs.append(r)
        if self.tool == "eval":
            if not (self.size and self.ref_spp and self.methods and self.runs):
                raise DeclarationError(f"{where}: an eval experiment needs size, ref_spp, methods and runs")
            for r in self.runs:
                frame_range(r["frames"])
        if self.tool == "bench" and not all("args" in r for r in self.runs):
            raise DeclarationError(f"{where}: every bench run needs args")
        if self.device_step and not all("device_csv" in r for r in self.runs):
            raise DeclarationError(f"{where}: a GPU experiment names each run's device_csv")
        self.results = os.path.join(results_dir, self.name + ".csv")
        self.tables = [Table(self, t) for t in d.get("table", [])]
        if not self.tables:
            raise DeclarationError(f"{where}: no table")

    def run_ids(self):
        return [r["id"] for r in self.runs]

    def metrics(self):
        """The metrics the tables read (for eval: the kept CSV's columns after the keys)."""
        return sorted({name for t in self.tables for name in t.metric_names()})

    def commands(self):
        """Each run's command as shown in the README: what decides the numbers, without the output paths."""
        if self.tool == "ctest":
            return ["ctest -L stability -V"]
        return [" ".join(r.get("env", []) + ["rtdr"] + self.rtdr_args(r)) for r in self.runs]

    def rtdr_args(self, run):
        """The arguments of `rtdr` for one run, without the output paths."""
        if self.tool == "bench":
            return list(run["args"])
        methods = ",".join(self.methods.values())
        return (["eval", "--scene", run["scene"], "--methods", methods, "--frames", run["frames"], "--size",
                 self.size, "--ref-spp", str(self.ref_spp)] + self.flags)

    def footer_command(self):
        return (f"bash tools/gpu_device.sh {self.device_step}" if self.device_step
                else f"tools/reproduce.py {self.name}")


class Table:
    """One [[experiment.table]]: the marker it lives between, its columns and its rows."""

    def __init__(self, experiment, d):
        where = f"experiment {experiment.name}, table"
        only_keys(where, d, ["marker", "readme", "columns", "rows", "mean_over", "each_row", "where",
                             "show_commands"])
        self.experiment = experiment
        self.marker = d.get("marker", experiment.name)
        self.readme = d["readme"]
        self.mean_over = d.get("mean_over")  # frames A-B averaged, for every row that does not say
        self.each_row = d.get("each_row", False)  # ctest: one row per line of the kept CSV
        self.where = list(d.get("where", []))    # ... whose claim starts with one of these
        self.show_commands = d.get("show_commands", True)
        self.columns = []
        for c in d["columns"]:
            only_keys(f"{where} {self.marker}, column", c, ["head", "cell", "best", "timing"])
            if c.get("best") not in (None, "min", "max"):
                raise DeclarationError(f"{where} {self.marker}: best is min or max")
            self.columns.append(c)
        self.rows = [dict(r) for r in d.get("rows", [])]
        # The row keys a cell prints as text: every key of a row but its selectors and the frames it averages.
        self.literal_keys = {k for r in self.rows for k in r if k not in SELECTORS + ("mean_over", "omit")}
        if self.each_row:
            self.literal_keys |= {"claim", "value", "threshold"}
        if not self.each_row and not self.rows:
            raise DeclarationError(f"{where} {self.marker}: no rows")
        for row in self.rows:
            for key in SELECTORS:
                if key in row and row[key] not in self.names(key):
                    raise DeclarationError(f"{where} {self.marker}: row selects {key} '{row[key]}', "
                                           "which is not declared")
        for row in self.rows:  # every field parses, every @name is known
            for c in self.columns:
                for field in fields(c["cell"]):
                    field = self.expand(field, row)
                    if not self.is_text(field):
                        self.parse_expression(field)

    def names(self, key):
        e = self.experiment
        if key == "run":
            return e.run_ids()
        if key == "method":
            return list(e.methods)
        return sorted({r.get("scene", "") for r in e.runs} | {s for r in e.runs for s in scenes_of_bench(r)})

    def expand(self, field, row):
        """A field with each $key replaced by the row's value: `{cpu_ms_$pass}` is `{cpu_ms_atrous}` in the row
        whose pass is "atrous", and a row's value may be a whole expression (`cpu_ms_a + cpu_ms_b`)."""
        def value(match):
            if match.group(1) not in row:
                raise DeclarationError(f"table {self.marker}: a row has no '{match.group(1)}' for ${match.group(1)}")
            return str(row[match.group(1)])
        return re.sub(r"\$(\w+)", value, field)

    def is_text(self, field):
        return field.split(":")[0] in BUILTINS or field.split(":")[0] in self.literal_keys

    def parse_expression(self, field):
        """'rmse@asvgf / rmse@svgf - 1:+.0%' -> (expression with terms t0, t1.., [(metric, {key: name})], format)."""
        expression, fmt = field, ""
        head, colon, tail = field.rpartition(":")
        if colon and re.fullmatch(r"[<>^=]?[+\- ]?#?0?\d*[,_]?(?:\.\d+)?[eEfFgGn%d]?", tail):
            expression, fmt = head, tail
        terms = []

        def term(match):
            metric, chosen = match.group(1), {}
            for name in match.group(2).split("@")[1:]:
                frames = re.fullmatch(r"(\d+)(?:_(\d+))?", name)  # @40: frame 40; @51_60: frames 51-60
                if frames:
                    chosen["frames"] = f"{frames.group(1)}-{frames.group(2) or frames.group(1)}"
                    continue
                keys = [k for k in SELECTORS if name in self.names(k)]
                if len(keys) != 1:
                    raise DeclarationError(f"table {self.marker}: '@{name}' names no run, method or scene"
                                           if not keys else f"table {self.marker}: '@{name}' is ambiguous")
                chosen[keys[0]] = name
            terms.append((metric, chosen))
            return f"t{len(terms) - 1}"

        code = re.sub(r"(?<![\w.])([A-Za-z_]\w*)((?:@\w+)*)", term, expression)
        try:
            tree = ast.parse(code, mode="eval")
        except SyntaxError:
            raise DeclarationError(f"table {self.marker}: '{{{field}}}' is not a field") from None
        check_arithmetic(tree.body, self.marker, field)
        return tree, terms, fmt

    def metric_names(self):
        if self.each_row:
            return []
        names = set()
        for row in self.rows:
            for c in self.columns:
                for field in fields(c["cell"]):
                    field = self.expand(field, row)
                    if not self.is_text(field):
                        names.update(metric for metric, _ in self.parse_expression(field)[1])
        return names

    def header(self):
        heads = [c["head"] for c in self.columns]
        return ["| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]


def scenes_of_bench(run):
    args = run.get("args", [])
    for k, a in enumerate(args[:-1]):
        if a == "--scenes":
            return args[k + 1].split(",")
    return []


def check_arithmetic(node, marker, field):
    allowed = (ast.BinOp, ast.UnaryOp, ast.Constant, ast.Name, ast.Add, ast.Sub, ast.Mult, ast.Div, ast.USub,
               ast.UAdd)
    for child in ast.walk(node):
        if not isinstance(child, allowed + (ast.Load,)):
            raise DeclarationError(f"table {marker}: '{{{field}}}' may hold only metrics, numbers and + - * /")


def fields(template):
    return re.findall(r"\{([^{}]+)\}", template)


def load(path):
    """The declaration file -> {name: Experiment}, every name and marker unique."""
    with open(path, "rb") as f:
        d = tomllib.load(f)
    only_keys(path, d, ["calibration", "experiment"])
    results_dir = os.path.join(os.path.dirname(os.path.abspath(path)), "results")
    experiments, markers = {}, set()
    for e in d.get("experiment", []):
        try:
            experiment = Experiment(e, results_dir)
        except (KeyError, TypeError) as error:
            raise DeclarationError(f"experiment {e.get('name', '?')}: missing or malformed {error}") from None
        if experiment.name in experiments:
            raise DeclarationError(f"experiment {experiment.name} is declared twice")
        for t in experiment.tables:
            if t.marker in markers:
                raise DeclarationError(f"marker {t.marker} is declared twice")
            markers.add(t.marker)
        experiments[experiment.name] = experiment
    return experiments, d.get("calibration", {})


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
