"""The .csg text: tokens and statements, and the reader's error."""

import re

__all__ = ['Parser', 'ReadError', 'Stmt', 'TOKEN', 'UNDEF']


# --------------------------------------------------------------------------
# Errors
# --------------------------------------------------------------------------


class ReadError(Exception):
    def __init__(self, path, line, col, msg):
        super().__init__(f"{path}:{line}:{col}: {msg}")


# --------------------------------------------------------------------------
# The .csg text: tokens and statements
# --------------------------------------------------------------------------

TOKEN = re.compile(
    r"""
    (?P<ws>[ \t\r\n]+)
  | (?P<comment>//[^\n]*|/\*.*?\*/)
  | (?P<number>[-+]?(?:(?:inf|nan)(?![A-Za-z0-9_])|(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?))
  | (?P<string>"(?:[^"\\]|\\.)*")
  | (?P<name>[$A-Za-z_][A-Za-z0-9_]*)
  | (?P<punct>[()\[\]{},;=#%*!])
    """,
    re.VERBOSE | re.DOTALL,
)

UNDEF = object()


class Stmt:
    def __init__(self, name, args, children, mods, line, col):
        self.name, self.args, self.children, self.mods = name, args, children, mods
        self.line, self.col = line, col


class Parser:
    def __init__(self, path, text):
        self.path = path
        self.toks = []
        pos, line, lstart = 0, 1, 0
        while pos < len(text):
            m = TOKEN.match(text, pos)
            if not m:
                raise ReadError(path, line, pos - lstart + 1, f"unexpected character {text[pos]!r}")
            kind = m.lastgroup
            if kind not in ("ws", "comment"):
                self.toks.append((kind, m.group(), line, pos - lstart + 1))
            for k, ch in enumerate(m.group()):
                if ch == "\n":
                    line, lstart = line + 1, pos + k + 1
            pos = m.end()
        self.toks.append(("eof", "", line, pos - lstart + 1))
        self.i = 0

    def peek(self):
        return self.toks[self.i]

    def take(self, value=None, kind=None):
        t = self.toks[self.i]
        if (value is not None and t[1] != value) or (kind is not None and t[0] != kind):
            want = value if value is not None else kind
            raise ReadError(self.path, t[2], t[3], f"expected {want!r}, found {t[1]!r}")
        self.i += 1
        return t

    def file(self):
        out = []
        while self.peek()[0] != "eof":
            if self.peek()[1] == ";":
                self.i += 1
                continue
            out.append(self.statement())
        return out

    def statement(self):
        mods = ""
        while self.peek()[1] in ("#", "%", "*", "!"):
            mods += self.take()[1]
        kind, name, line, col = self.take(kind="name")
        self.take("(")
        args = []
        while self.peek()[1] != ")":
            if self.peek()[0] == "name" and self.toks[self.i + 1][1] == "=":
                key = self.take()[1]
                self.take("=")
                args.append((key, self.value()))
            else:
                args.append((None, self.value()))
            if self.peek()[1] == ",":
                self.i += 1
            elif self.peek()[1] != ")":
                t = self.peek()
                raise ReadError(self.path, t[2], t[3], f"expected ',' or ')', found {t[1]!r}")
        self.take(")")
        children = []
        t = self.peek()
        if t[1] == ";":
            self.i += 1
        elif t[1] == "{":
            self.i += 1
            while self.peek()[1] != "}":
                if self.peek()[1] == ";":
                    self.i += 1
                    continue
                if self.peek()[0] == "eof":
                    raise ReadError(self.path, t[2], t[3], "this block is never closed")
                children.append(self.statement())
            self.i += 1
        else:
            children.append(self.statement())
        return Stmt(name, args, children, mods, line, col)

    def value(self):
        kind, text, line, col = self.peek()
        self.i += 1
        if kind == "number":
            return float(text)
        if kind == "string":
            return re.sub(r"\\(.)", r"\1", text[1:-1])
        if kind == "name" and text in ("true", "false"):
            return text == "true"
        if kind == "name" and text == "undef":
            return UNDEF
        if text == "[":
            out = []
            while self.peek()[1] != "]":
                out.append(self.value())
                if self.peek()[1] == ",":
                    self.i += 1
                elif self.peek()[1] != "]":
                    t = self.peek()
                    raise ReadError(self.path, t[2], t[3], f"expected ',' or ']', found {t[1]!r}")
            self.i += 1
            return out
        raise ReadError(self.path, line, col, f"expected a value, found {text!r}")
