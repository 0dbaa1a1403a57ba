"""The declarations of eval/experiments.toml: each experiment's commands, and its tables as templates.

A table cell is a template: text with fields in braces. `{label}` is the row's own text (any key of the row
but its selectors), or `{frames}`, `{scene}`, `{spec}`: its run's frames and scene, its method's spec.
`{rmse:.4f}` is a metric, the mean over the row's records (NaN and empty values skipped): `{rmse@asvgf}`
selects the method, run or scene named after the @ instead of the row's, `{rmse@40}` frame 40 and
`{rmse@51_60}` frames 51-60 instead of the row's `mean_over`. A field may be arithmetic on
metrics and numbers, `{rmse@asvgf / rmse@svgf - 1:+.0%}`, and `$key` inside a field is the row's value of
that key, text pasted in before the field is read (`{cpu_ms_$pass}`). Everything is checked when the
declaration is loaded: an unknown key, a field that does not parse, an @name that names nothing.
"""
import ast
import os
import re
import tomllib

TOOLS = ("eval", "bench", "ctest")
SELECTORS = ("run", "method", "scene")  # the row keys that choose records rather than print text
BUILTINS = ("frames", "scene", "spec")   # the row fields that come from the run or the method


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
