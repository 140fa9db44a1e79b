"""Mutant generation for C++ sources by text rules (docs/mutation.md).

A mutant is one edit of one source file: (path, start, end, replacement) in the file's text,
with a rule name and a stable id. Positions come from a masked copy of the text in which
comments, string and character literals and preprocessor lines are blanked, so no rule fires
inside them. The rules are plain text patterns over that copy; a mutant that does not compile
is "stillborn" and does not count.
"""
import bisect
import hashlib
import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Mutant:
    path: str         # repository-relative
    start: int        # byte offsets in the original text
    end: int
    replacement: str
    rule: str
    line: int         # 1-based, for reports
    id: str           # stable across unrelated edits: file, rule, the line's text, occurrence

    def apply(self, text):
        return text[:self.start] + self.replacement + text[self.end:]


def mask(text):
    """The text with comments, string/char literals and preprocessor lines replaced by spaces
    (newlines kept), so offsets stay those of the original."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            i += 1
            continue
        if line_start and c == "#":
            # a preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out[i] = " "
                    i += 2
                    continue
                out[i] = " "
                i += 1
            continue
        line_start = False
        if c == "\n":
            line_start = True
            i += 1
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                out[i] = " "
                i += 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            for k in range(i, j):
                if out[k] != "\n":
                    out[k] = " "
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                i += 1
                continue
            close = ")" + m.group(1) + '"'
            j = text.find(close, i + m.end())
            j = n if j < 0 else j + len(close)
            for k in range(i, j):
                if out[k] != "\n":
                    out[k] = " "
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():
                i += 1  # a digit separator (1'000)
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            for k in range(i, j):
                out[k] = " "
            i = j
        else:
            i += 1
    return "".join(out)


# Functions whose two arguments commute exactly (each product a·b = b·a in IEEE arithmetic, the
# sum in the same order): swapping them is always an equivalent mutant.
SYMMETRIC = {"dot", "distance"}

# Binary operators written with a space on each side (the code's format), and their swaps.
OPERATOR_SWAPS = {
    "<": ["<=", ">"], "<=": ["<", ">="], ">": [">=", "<"], ">=": [">", "<="],
    "==": ["!="], "!=": ["=="],
    "+": ["-"], "-": ["+"], "*": ["/"], "/": ["*"],
    "&&": ["||"], "||": ["&&"],
    "+=": ["=", "-="], "-=": ["=", "+="], "*=": ["="], "/=": ["="],
}
OP_RE = re.compile(r"(?<=[\w)\]]) (<=|>=|==|!=|&&|\|\||\+=|-=|\*=|/=|<|>|\+|-|\*|/) (?=[\w(!\-.])")
NUM_RE = re.compile(r"(?<![\w.])(\d+\.\d*|\.\d+|\d+)([eE][-+]?\d+)?([fFuUlL]*)(?![\w.])")
CALL2_RE = re.compile(r"\b([A-Za-z_][\w:]*)\(([A-Za-z_][\w.]*(?:\[[\w]+\])?), ([A-Za-z_][\w.]*(?:\[[\w]+\])?)([,)])")
MINMAX_RE = re.compile(r"\bstd::(min|max|clamp)\(")
EARLY_RE = re.compile(r"^[ \t]*if \(.*\) (return\b[^;]*|continue|break);[ \t]*$", re.M)
KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "static_cast", "reinterpret_cast",
            "const_cast", "decltype", "alignof", "static_assert", "catch"}


def _matching_paren(masked, open_pos):
    depth = 0
    for k in range(open_pos, len(masked)):
        if masked[k] in "([{":
            depth += 1
        elif masked[k] in ")]}":
            depth -= 1
            if depth == 0:
                return k
    return -1


def _split_args(masked, open_pos, close_pos):
    """[(start, end)] of the top-level comma-separated arguments inside (open_pos, close_pos)."""
    args, depth, s = [], 0, open_pos + 1
    for k in range(open_pos + 1, close_pos):
        c = masked[k]
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            args.append((s, k))
            s = k + 1
    args.append((s, close_pos))
    return [(a + (len(masked[a:b]) - len(masked[a:b].lstrip())), b) for a, b in args]


# What ends an operand at depth 0: a term ends at the next spaced + or -, a logical or
# relational operator, or , ; ? :; a factor also at a space (the next operator).
_TERM_STOPS = (" + ", " - ", " && ", " || ", " < ", " > ", " <= ", " >= ", " == ", " != ")


def _operand_end(masked, start, factor):
    """End of the operand of +/- (factor False) or of * and / (factor True) that starts at
    `start`: at the stops above, or at the bracket that closes an enclosing group; a factor
    that is a whole bracketed group (a call, a parenthesis) ends after it."""
    depth = 0
    k = start
    while k < len(masked):
        c = masked[k]
        if c in "([{":
            depth += 1
        elif c in ")]}":
            if depth == 0:
                return k
            depth -= 1
            if factor and depth == 0 and k + 1 < len(masked) and not (masked[k + 1].isalnum() or masked[k + 1] in "._[("):
                return k + 1
        elif depth == 0 and (c in ",;?:" or (c == " " if factor else masked.startswith(_TERM_STOPS, k))):
            return k
        k += 1
    return k


def _constants(lit, exp, suffix):
    """Replacements for a numeric literal: 0, ×2, +1, −1 (as literals of the same kind)."""
    is_float = "." in lit or bool(exp)
    try:
        v = float(lit + (exp or "")) if is_float else int(lit)
    except ValueError:
        return []
    out = []
    cands = [0, v * 2, v + 1, v - 1] if v != 0 else [1]
    for c in cands:
        if c == v or (not is_float and c < 0):
            continue
        if is_float:
            s = repr(float(c))
            if "e" in s or "E" in s:
                s = f"{float(c):.17g}"
                if "." not in s and "e" not in s:
                    s += ".0"
        else:
            s = str(int(c))
        s += suffix
        if s not in out:
            out.append(s)
    return out


def generate(path, text):
    """Every mutant of one file, in file order."""
    m = mask(text)
    line_starts = [0] + [i + 1 for i, c in enumerate(text) if c == "\n"]

    def line_of(pos):
        return bisect.bisect_right(line_starts, pos)

    raw = []
    for mo in OP_RE.finditer(m):
        op = mo.group(1)
        s, e = mo.start(1), mo.end(1)
        for rep in OPERATOR_SWAPS[op]:
            raw.append((s, e, rep, f"op {op} -> {rep}"))
        if op in ("+", "-", "*", "/"):
            # drop the right-hand term or factor: "a + b" -> "a"
            te = _operand_end(m, e + 1, factor=op in "*/")
            if te > e + 1:
                raw.append((mo.start(), te, "", f"drop {op} term"))
    for mo in NUM_RE.finditer(m):
        lit, exp, suffix = mo.group(1), mo.group(2) or "", mo.group(3) or ""
        # every literal, array sizes and template arguments included: one that cannot change
        # does not compile (stillborn)
        for rep in _constants(lit, exp, suffix):
            raw.append((mo.start(), mo.end(), rep, f"const {lit}{exp} -> {rep}"))
    for mo in CALL2_RE.finditer(m):
        if mo.group(1).split("::")[-1] in KEYWORDS | SYMMETRIC:
            continue
        a, b = mo.group(2), mo.group(3)
        if a == b:
            continue
        s, e = mo.start(2), mo.end(3)
        raw.append((s, e, f"{b}, {a}", f"swap args of {mo.group(1)}"))
    for mo in MINMAX_RE.finditer(m):
        open_pos = mo.end() - 1
        close = _matching_paren(m, open_pos)
        if close < 0:
            continue
        args = _split_args(m, open_pos, close)
        name = mo.group(1)
        if name == "clamp" and len(args) == 3:
            raw.append((mo.start(), close + 1, text[args[0][0]:args[0][1]], "drop clamp"))
        elif name in ("min", "max") and len(args) == 2:
            for a in args:
                raw.append((mo.start(), close + 1, text[a[0]:a[1]], f"drop {name} -> one argument"))
    for mo in EARLY_RE.finditer(m):
        raw.append((mo.start(), mo.end(), "", "drop early exit"))

    seen = {}
    out = []
    for s, e, rep, rule in sorted(raw, key=lambda r: (r[0], r[1], r[3], r[2])):
        if text[s:e] == rep:
            continue
        ln = line_of(s)
        line_end = text.find("\n", s)
        line_text = text[line_starts[ln - 1]:line_end if line_end >= 0 else len(text)]
        key = (rule, rep, line_text.strip())
        seen[key] = seen.get(key, 0) + 1
        h = hashlib.sha1("\0".join([path, rule, rep, line_text.strip(), str(seen[key])]).encode()).hexdigest()[:12]
        out.append(Mutant(path, s, e, rep, rule, ln, h))
    return out

