#!/usr/bin/python3
"""Checks that every reference the documentation and the comments make is true (ctest: `references`).

Usage: check_references.py SOURCE_DIR RTDR_EXE

It reads every *.md file, the markdown cells and code comments of every notebook, and the comments (and
Python docstrings) of every *.h, *.cpp, *.comp, *.glsl, *.py, *.sh, CMakeLists.txt and bash script of the
repository, and checks four kinds of reference:

  1. Paths. A word that starts with a top-level folder (`filters/svgf/atrous.cpp`, `raster/`) must exist;
     `core/exr_io` names the files core/exr_io.*. `<name>` and `*` are wildcards that must match at least one
     file, and `stem.{h,cpp}` names two files. A word that starts with ../ or ./ is read from the file's own
     folder. A bare file name with a source extension (`atrous.comp`, `svgf_params.h`) must be the name of
     some file of the repository.
  2. Links and sections. A markdown link to a local file must reach it, and `file.md#anchor` must name one of
     its headings. So must a quoted section after a markdown file's name, written in any of these ways:
     docs/x.md ("Title"), docs/x.md, "Title", docs/x.md's "Title", docs/x.md, section "Title". The quoted
     words may begin a longer heading ("Packed illumination" for "Packed illumination: fp16 records").
  3. CLI flags. A `--flag` must be printed by `rtdr --help` or by the --help of a subcommand: of the
     subcommand named before it on the same line (`rtdr probe ... --json`) when there is one, else of any.
     A flag that follows another program's name on its line (FOREIGN_PROGRAMS: `ctest --output-on-failure`)
     is that program's and is not checked; one that follows a script of ours as it is run (`bash
     tools/fuzz.sh --runs=N`, or by its path, `tools/reproduce.py --check`) must appear in that script, and so
     must a flag in a script's own comments.
     A placeholder is a wildcard: `--<name>` matches any flag.
  4. Things outside the repository: issue numbers ("issue 6", "issue #12"), the team's notes (TOOLCHAIN.md,
     DESIGN.md, STYLE.md), ../shared and seeds/. A reader of the repository has none of them.
  5. One claim, that docs/architecture.md lists every port: each shader of the repository (*.comp) is named
     there, so a new port cannot be missing from its list of which passes have ports.

To keep false findings rare, only words that start with a folder of the repository are read as paths (so
out/demo/ and build/app/rtdr are not), and a bare `n.h` or `wo.h` (one or two letters) is a dot product with
the half vector, not a header. Files are those git lists (tracked, or new and not ignored), or, outside a git
checkout, every file but build*/, out/, .git/, .gl/ and .deps/. Code and string literals are not read.

Prints one line per finding, `file:line: what`, and exits 1 when there is any.
"""
import fnmatch
import json
import os
import re
import subprocess
import sys
import tokenize

# Folders of the repository that a path may start with. The folders at the top of the source tree are added
# to these, so a new folder is checked without editing this list; a folder named here that no longer exists
# makes every path into it a finding.
TOP_FOLDERS = ["app", "core", "docs", "eval", "filters", "fuzz", "gpu", "motion", "notebooks", "raster",
               "scenes", "tests", "tools", "trace", ".ci"]
# Outside a git checkout: folders at the top that are not the repository's (build trees, outputs, downloads),
# and folders anywhere that tools leave behind.
NOT_OURS_AT_TOP = re.compile(r"^(build.*|out|\.git|\.gl|\.deps)$")
NOT_OURS_ANYWHERE = {"__pycache__", ".ipynb_checkpoints"}

# Extensions of the files whose bare names are checked (rule 1).
SOURCE_EXTENSIONS = ["h", "cpp", "comp", "glsl", "py", "sh", "md", "ipynb"]

# Programs whose flags are their own: a flag after one of these names on its line is not checked (rule 3).
FOREIGN_PROGRAMS = ["cmake", "ctest", "git", "glslc", "jupyter-nbconvert", "jupyter", "nbconvert", "valgrind",
                    "callgrind_annotate", "apt-get", "apt", "nvidia-smi", "ninja", "clang", "clang++", "pip",
                    "dask", "dask-scheduler", "dask-worker", "sbatch", "SBATCH"]

# References to what only the team has, outside the repository (rule 4). "a level issues 36 loads" is a verb.
OUTSIDE = [
    (re.compile(r"\bissue\s+#?\d+|\bissues\s+#?\d+\s*(?:,|and)\s*#?\d+|\b(?:PR|pull request)\s+#?\d+", re.I),
     "names an issue of the team's tracker, which is not in the repository"),
    (re.compile(r"\b(?:TOOLCHAIN|DESIGN|STYLE)\.md\b"), "names a team note that is not in the repository"),
    (re.compile(r"\.\./shared\b"), "names ../shared, a folder outside the repository"),
    (re.compile(r"(?<![\w/.-])seeds/"), "names seeds/, a folder outside the repository"),
]

# The characters of a path: letters, digits, _ . - / and *, placeholders like <stem>, and braces {h,cpp}.
PATH_CHARS = r"(?:[\w.\-/*]|<[\w-]+>|\{[\w.,-]+\})"
# What may not come just before a path (so `build/app/rtdr` is not read as `app/rtdr`).
NOT_BEFORE_PATH = r"(?<![\w./\-~$@])"


def outside_reference(word):
    return any(pattern.search(word) for pattern, _ in OUTSIDE)


class Repo:
    """The files of the source tree, and the findings made so far."""

    def __init__(self, root):
        self.root = os.path.abspath(root)
        self.files = self.list_files()  # paths relative to root, with '/'
        self.basenames = {f.rsplit("/", 1)[-1] for f in self.files}
        self.folders = set()
        for f in self.files:
            while "/" in f:
                f = f.rsplit("/", 1)[0]
                self.folders.add(f)
        tops = set(TOP_FOLDERS) | {f for f in self.folders if "/" not in f}
        self.top_folders = sorted(tops, key=len, reverse=True)  # longest first, for the regular expressions
        self.findings = []  # (path, line, what)

    def list_files(self):
        git = subprocess.run(["git", "-C", self.root, "ls-files", "--cached", "--others", "--exclude-standard"],
                             capture_output=True, text=True)
        if git.returncode == 0 and git.stdout:
            return sorted(f for f in git.stdout.split("\n")
                          if f and os.path.isfile(os.path.join(self.root, f))
                          and not NOT_OURS_ANYWHERE.intersection(f.split("/")))
        files = []
        for folder, subfolders, names in os.walk(self.root):
            top = folder == self.root
            subfolders[:] = sorted(d for d in subfolders
                                   if d not in NOT_OURS_ANYWHERE and not (top and NOT_OURS_AT_TOP.match(d)))
            for name in sorted(names):
                files.append(os.path.relpath(os.path.join(folder, name), self.root).replace(os.sep, "/"))
        return files

    def find(self, path, line, what):
        self.findings.append((path, line, what))

    def exists(self, relative):
        """Whether a repository path exists; `*` matches any run of characters, a final '/' means a folder."""
        folder_only = relative.endswith("/")
        relative = relative.rstrip("/")
        candidates = self.folders if folder_only else self.folders | set(self.files)
        if relative == "":
            return True
        if "*" not in relative:
            return relative in candidates
        return any(fnmatch.fnmatchcase(p, relative) for p in candidates)

    def read(self, relative):
        with open(os.path.join(self.root, relative), encoding="utf-8", errors="replace") as f:
            return f.read()


# ---- The prose of each file, with its line numbers ----------------------------------------------------------

class Text:
    """A run of prose (a block of comment lines, a markdown file) as one string, with the line each part is on,
    so that a reference wrapped over two lines is still read whole."""

    def __init__(self):
        self.text = ""
        self.lines = []  # (offset in text, line number in the file), one per added line

    def add(self, line_number, line):
        if self.text:
            self.text += "\n"
        self.lines.append((len(self.text), line_number))
        self.text += line

    def line_of(self, offset):
        number = self.lines[0][1]
        for start, line_number in self.lines:
            if start > offset:
                break
            number = line_number
        return number

    def line_around(self, offset):
        """The line that the character at `offset` is on, and the character's column in it."""
        start = self.text.rfind("\n", 0, offset) + 1
        end = self.text.find("\n", offset)
        return (self.text[start:] if end < 0 else self.text[start:end]), offset - start


class Blocks:
    """Comment lines grouped into Texts: a line right below the previous comment line continues its block."""

    def __init__(self):
        self.texts = []
        self.last_line = None

    def add(self, line_number, line):
        if self.last_line != line_number - 1:
            self.texts.append(Text())
        self.texts[-1].add(line_number, line)
        self.last_line = line_number


def c_comments(source):
    """The comments of C++ or GLSL source: each block of // lines, and each /* */ comment, as one Text."""
    blocks = Blocks()
    i, line, n = 0, 1, len(source)
    while i < n:
        if source[i] == "\n":
            line += 1
            i += 1
        elif source.startswith("//", i):
            end = source.find("\n", i)
            end = n if end < 0 else end
            blocks.add(line, source[i + 2:end])
            i = end
        elif source.startswith("/*", i):
            end = source.find("*/", i + 2)
            end = n if end < 0 else end
            for k, part in enumerate(source[i + 2:end].split("\n")):
                blocks.add(line + k, part)
            blocks.last_line = None  # a /* */ comment is a block of its own
            line += source.count("\n", i, end)
            i = end + 2
        elif source.startswith('R"', i) and (i == 0 or not (source[i - 1].isalnum() or source[i - 1] == "_")):
            open_paren = source.find("(", i)  # a raw string R"delimiter( ... )delimiter"
            closing = ")" + source[i + 2:open_paren] + '"'
            end = source.find(closing, open_paren)
            end = n if end < 0 else end + len(closing)
            line += source.count("\n", i, end)
            i = end
        elif source[i] == '"' or (source[i] == "'" and not (i > 0 and source[i - 1].isdigit())):  # 999'999
            quote, j = source[i], i + 1
            while j < n and source[j] != quote and source[j] != "\n":
                j += 2 if source[j] == "\\" else 1
            i = j + 1 if j < n and source[j] == quote else j
        else:
            i += 1
    return blocks.texts


def hash_comments(source, shell):
    """The # comments of a shell script or a CMake file. In a shell script a # starts a comment only at the
    start of a word ($#, ${#x} are not comments)."""
    blocks = Blocks()
    for number, line in enumerate(source.split("\n"), 1):
        if number == 1 and line.startswith("#!"):
            continue
        quote, k = None, 0
        while k < len(line):
            c = line[k]
            if quote:
                if c == "\\" and quote == '"':
                    k += 1  # skip the escaped character
                elif c == quote:
                    quote = None
            elif c in "\"'":
                quote = c
            elif c == "#" and (not shell or k == 0 or line[k - 1] in " \t;|&("):
                blocks.add(number, line[k + 1:])
                break
            k += 1
    return blocks.texts


def python_comments(source):
    """The # comments of Python source, and its docstrings (a string that is a statement of its own)."""
    blocks = Blocks()
    lines = iter(source.splitlines(keepends=True))
    previous = tokenize.NEWLINE
    try:
        for token in tokenize.generate_tokens(lambda: next(lines, "")):
            if token.type == tokenize.COMMENT:
                blocks.add(token.start[0], token.string[1:])
            elif token.type == tokenize.STRING and previous in (tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT):
                for k, part in enumerate(token.string.split("\n")):
                    blocks.add(token.start[0] + k, part)
                blocks.last_line = None
            if token.type not in (tokenize.COMMENT, tokenize.NL):
                previous = token.type
    except (tokenize.TokenError, SyntaxError):
        pass  # a cell that is not whole Python: what was read so far is kept
    return blocks.texts


def markdown_texts(source):
    text = Text()
    for number, line in enumerate(source.split("\n"), 1):
        text.add(number, line)
    return [text]


def notebook_texts(source):
    """A notebook's markdown cells, and the comments of its code cells, with their lines in the .ipynb file."""
    raw_lines = source.split("\n")
    cursor = 0

    def raw_line_of(part):  # nbformat writes each line of a cell's source on a line of the file of its own
        nonlocal cursor
        quoted = json.dumps(part)[1:-1]
        for k in range(cursor, len(raw_lines)):
            if quoted in raw_lines[k]:
                cursor = k
                return k + 1
        return cursor + 1

    texts = []
    for cell in json.loads(source).get("cells", []):
        cell_source = "".join(cell.get("source", []))
        parts = cell_source.split("\n")
        numbers = [raw_line_of(part) for part in parts]
        if cell.get("cell_type") == "markdown":
            text = Text()
            for number, part in zip(numbers, parts):
                text.add(number, part)
            texts.append(text)
        elif cell.get("cell_type") == "code":
            for text in python_comments(cell_source):
                text.lines = [(start, numbers[n - 1]) for start, n in text.lines]
                texts.append(text)
    return texts


def prose_of(repo, path):
    """("markdown" or "comment", [Text]) for a file whose prose is checked, else None."""
    name = path.rsplit("/", 1)[-1]
    extension = name.rsplit(".", 1)[-1] if "." in name else ""
    if extension == "md":
        return "markdown", markdown_texts(repo.read(path))
    if extension == "ipynb":
        return "markdown", notebook_texts(repo.read(path))
    if extension in ("h", "cpp", "comp", "glsl"):
        return "comment", c_comments(repo.read(path))
    if extension == "py":
        return "comment", python_comments(repo.read(path))
    if name == "CMakeLists.txt" or extension == "cmake":
        return "comment", hash_comments(repo.read(path), shell=False)
    if extension == "sh" or (extension == "" and repo.read(path).startswith("#!/usr/bin/env bash")):
        return "comment", hash_comments(repo.read(path), shell=True)
    return None


# ---- 1. Paths -----------------------------------------------------------------------------------------------

def expand_braces(word):
    """`temporal.{h,cpp}` -> [`temporal.h`, `temporal.cpp`]."""
    match = re.search(r"\{([^{}]*)\}", word)
    if not match:
        return [word]
    return [expanded for choice in match.group(1).split(",")
            for expanded in expand_braces(word[:match.start()] + choice + word[match.end():])]


def as_pattern(word):
    """Placeholders (`<stem>`) become wildcards, and the punctuation that ends a sentence is dropped."""
    return re.sub(r"<[\w-]+>", "*", word).rstrip(".,")


def check_path(repo, path, text, offset, word, folder):
    """`word` names files from `folder` ("" for the repository's root)."""
    for name in expand_braces(as_pattern(word)):
        joined = os.path.normpath(os.path.join(folder, name)).replace(os.sep, "/")
        if name.endswith("/"):
            joined += "/"
        if joined.startswith(".."):
            repo.find(path, text.line_of(offset), f"'{name}' leads outside the repository")
        elif not repo.exists(joined) and not repo.exists(joined + ".*"):
            repo.find(path, text.line_of(offset), f"names '{name}', which does not exist")


def check_paths(repo, path, text):
    folder = path.rsplit("/", 1)[0] if "/" in path else ""
    tops = "|".join(re.escape(t) for t in repo.top_folders)
    for match in re.finditer(NOT_BEFORE_PATH + r"(?:%s)/%s*" % (tops, PATH_CHARS), text.text):
        if not outside_reference(match.group(0)):  # else rule 4 reports it
            check_path(repo, path, text, match.start(), match.group(0), "")
    for match in re.finditer(NOT_BEFORE_PATH + r"\.\.?/%s+" % PATH_CHARS, text.text):
        if not outside_reference(match.group(0)):
            check_path(repo, path, text, match.start(), match.group(0), folder)

    extensions = "|".join(SOURCE_EXTENSIONS)
    bare = r"(?<![\w./\-<>*$@{])(?:[\w-]|<[\w-]+>)+(?:\.\{[\w,]+\}|\.(?:%s)|Lists\.txt)(?![\w\-/.]*\w)" % extensions
    for match in re.finditer(bare, text.text):
        word = match.group(0)
        if re.fullmatch(r"<[\w-]+>\..*", word):
            continue  # no more than a placeholder: `<stem>.cpp`
        if re.fullmatch(r"\w{1,2}\.h", word):
            continue  # a dot product with the half vector (`n.h`, `wo.h` in trace/brdf.h), not a header
        if (word.endswith("Lists.txt") and word != "CMakeLists.txt") or outside_reference(word):
            continue
        for name in expand_braces(word):
            if not any(fnmatch.fnmatchcase(b, as_pattern(name)) for b in repo.basenames):
                repo.find(path, text.line_of(match.start()), f"names '{name}', which is no file of the repository")


# ---- 2. Links and sections ----------------------------------------------------------------------------------

def normalise_title(title):
    return " ".join(re.sub(r"[`*_]", "", title).lower().split())


def headings(repo, md_path):
    """The headings of a markdown file: their titles (normalised) and their anchors as GitHub makes them."""
    titles, anchors, fenced = [], [], False
    for line in repo.read(md_path).split("\n"):
        if line.startswith("```"):
            fenced = not fenced
        match = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not match:
            continue
        titles.append(normalise_title(match.group(1)))
        anchor = re.sub(r"[^\w\- ]", "", match.group(1).lower()).replace(" ", "-")
        count = sum(1 for a in anchors if a == anchor or re.fullmatch(re.escape(anchor) + r"-\d+", a))
        anchors.append(anchor if count == 0 else f"{anchor}-{count}")  # a repeated title gets -1, -2, ...
    return titles, anchors


def markdown_file(repo, path, word):
    """The markdown file that `word` names from `path`: relative to the file's folder, else to the root, else
    the only file of that name. None when there is none."""
    folder = path.rsplit("/", 1)[0] if "/" in path else ""
    for candidate in (os.path.join(folder, word), word):
        candidate = os.path.normpath(candidate).replace(os.sep, "/")
        if candidate in repo.files:
            return candidate
    same_name = [f for f in repo.files if f.rsplit("/", 1)[-1] == word]
    return same_name[0] if len(same_name) == 1 else None


def check_links(repo, path, text):
    folder = path.rsplit("/", 1)[0] if "/" in path else ""
    for match in re.finditer(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", text.text):
        target = match.group(1)
        if re.match(r"[a-z]+:", target):
            continue  # http:, https:, mailto:
        file_part, _, anchor = target.partition("#")
        linked = path
        if file_part:
            linked = os.path.normpath(os.path.join(folder, file_part)).replace(os.sep, "/")
            if linked.startswith("..") or not repo.exists(linked):
                repo.find(path, text.line_of(match.start()), f"links to '{target}', which does not exist")
                continue
        if anchor and linked.endswith(".md") and anchor not in headings(repo, linked)[1]:
            repo.find(path, text.line_of(match.start()), f"links to '{target}': no heading has that anchor")


def check_sections(repo, path, text):
    quoted = r"[\"“]([^\"”]+)[\"”]"
    section = r"([\w./\-]+\.md)(?:\s*\(\s*(?:section\s+)?|,\s*(?:section\s+)?|'s\s+|\s+section\s+)" + quoted
    for match in re.finditer(section, text.text, re.I):
        md = markdown_file(repo, path, match.group(1))
        if md is None:
            continue  # a file that does not exist is reported as a path
        wanted = normalise_title(match.group(2))  # a title wrapped over two lines is joined
        if not any(title == wanted or re.match(re.escape(wanted) + r"\b", title) for title in headings(repo, md)[0]):
            title = " ".join(match.group(2).split())
            repo.find(path, text.line_of(match.start()), f"names section \"{title}\" of {md}, which has no such heading")


# ---- 3. CLI flags -------------------------------------------------------------------------------------------

def help_of(rtdr, words):
    """The flags and the subcommands that `rtdr WORDS --help` prints."""
    result = subprocess.run([rtdr] + words + ["--help"], capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        sys.exit(f"check_references: '{' '.join([rtdr] + words)} --help' failed: {result.stderr.strip()}")
    flags, subcommands, section = set(), [], ""
    for line in result.stdout.split("\n"):
        if line.endswith(":") and not line.startswith(" "):
            section = line  # "Options:", "Subcommands:", "SVGF parameters:"
        elif section == "Subcommands:":
            subcommands += re.findall(r"^\s+([\w-]+)\s", line)
        else:
            flags.update(re.findall(r"^\s+(?:-\w,)?(--[\w.\-]+)", line))
    return flags, subcommands


def rtdr_flags(rtdr):
    """{subcommand: its flags and the global ones}; the key "" holds the global flags alone."""
    global_flags, subcommands = help_of(rtdr, [])
    flags = {"": global_flags}
    for sub in subcommands:
        flags[sub] = help_of(rtdr, [sub])[0] | global_flags
    return flags


def command_pattern(flags, scripts):
    """Matches the name of a command: `rtdr` with its subcommand (group 1), another program (group 2), or a
    script of ours where it is run: after bash or python3 (group 3), or one of tools/ by its path (group 4)."""
    alternatives = lambda names: "|".join(re.escape(n) for n in sorted(names, key=len, reverse=True))
    by_path = [name for name in scripts if name.startswith("tools/")]
    return re.compile(r"(?<![\w\-])(?:rtdr(?:\s+(%s))?|(%s)|(?:(?<=bash )|(?<=python3 ))(%s)|(?<![\w./\-])(%s))"
                      r"(?![\w\-])" % (alternatives(s for s in flags if s), alternatives(FOREIGN_PROGRAMS),
                                       alternatives(scripts), alternatives(by_path)))


def check_flags(repo, path, text, flags, scripts, command):
    every_flag = set().union(*flags.values())
    for match in re.finditer(r"(?<![\w\-])--[A-Za-z](?:[\w.\-]|<[\w-]+>)*", text.text):
        flag = match.group(0).rstrip(".-")
        line, column = text.line_around(match.start())
        commands = [m for m in command.finditer(line) if m.end() <= column]
        last = commands[-1] if commands else None
        if last and last.group(2):
            continue  # another program's flag
        if last:
            script = scripts[last.group(3) or last.group(4)] if last.group(3) or last.group(4) else None
        else:
            script = path if path in scripts else None
        if script:
            # A flag of a script we run, or one in a script's own comments: the script must use it.
            if flag not in code_of(repo, script):
                repo.find(path, text.line_of(match.start()), f"'{flag}' is not a flag of {script}")
            continue
        subcommand = last.group(1) if last and last.group(1) else None
        known = flags[subcommand] if subcommand else every_flag
        pattern = re.compile(r"[\w.\-]+".join(re.escape(part) for part in re.split(r"<[\w-]+>", flag)) + "$")
        if not any(pattern.match(f) for f in known):
            where = f"rtdr {subcommand}" if subcommand else "rtdr"
            repo.find(path, text.line_of(match.start()), f"'{flag}' is not a flag of {where} (see its --help)")


def our_scripts(repo):
    """{name: path} of the repository's scripts, by path and by base name."""
    scripts = {}
    for f in repo.files:
        if f.endswith((".sh", ".py")):
            scripts[f] = f
            scripts[f.rsplit("/", 1)[-1]] = f
    return scripts


def code_of(repo, script):
    """A script's text without its comments."""
    source = repo.read(script)
    texts = python_comments(source) if script.endswith(".py") else hash_comments(source, shell=True)
    lines = source.split("\n")
    for text in texts:
        for start, number in text.lines:
            end = text.text.find("\n", start)
            comment = text.text[start:] if end < 0 else text.text[start:end]
            lines[number - 1] = lines[number - 1].replace(comment, "", 1)
    return "\n".join(lines)


# ---- 4. Outside the repository ------------------------------------------------------------------------------

def check_outside(repo, path, text):
    for pattern, what in OUTSIDE:
        for match in pattern.finditer(text.text):
            repo.find(path, text.line_of(match.start()), f"'{match.group(0)}' {what}")


# ---- 5. Every port in the architecture's list -------------------------------------------------------------

def check_ports_listed(repo):
    architecture = "docs/architecture.md"
    if architecture not in repo.files:
        return
    text = repo.read(architecture)
    for shader in sorted(f for f in repo.files if f.endswith(".comp")):
        name = shader.rsplit("/", 1)[-1]
        if not re.search(r"(?<![\w.-])" + re.escape(name) + r"(?![\w-])", text):
            repo.find(architecture, 1, f"does not name the port {shader} among the passes that have ports")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    repo = Repo(sys.argv[1])
    flags = rtdr_flags(sys.argv[2])
    scripts = our_scripts(repo)
    command = command_pattern(flags, scripts)
    for path in repo.files:
        if path == "tests/check_references.py":
            continue  # its own comments name what it looks for
        prose = prose_of(repo, path)
        if prose is None:
            continue
        kind, texts = prose
        for text in texts:
            check_paths(repo, path, text)
            if kind == "markdown":
                check_links(repo, path, text)
            check_sections(repo, path, text)
            check_flags(repo, path, text, flags, scripts, command)
            check_outside(repo, path, text)
    check_ports_listed(repo)
    for path, line, what in sorted(set(repo.findings)):
        print(f"{path}:{line}: {what}")
    if repo.findings:
        print(f"check_references: {len(set(repo.findings))} false references")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
