#!/usr/bin/env python3
"""No function or lambda body over 60 lines in the sources of lib/, gtr/, experiments/ and bench/.

    function_lengths.py [--root DIR] [--allow FILE] [--limit N]   the check (exit 1 naming each offender)
    function_lengths.py --list [--root DIR] [--limit N]            every body over the limit, allowed or not
    function_lengths.py --self-test                                the scanner on small inline samples

A body's length counts from the line of its opening brace to the line of its closing brace. A lambda counts on its
own and also within the function that holds it; class bodies, namespaces, control blocks and brace initialisers
are not functions. The scanner reads C++ as tokens with comments, string and character literals (raw strings
included) and preprocessor lines taken out, and tells a body from the other braces by what comes before it.

The allow-list (tests/function_lengths_allow.txt) names bodies known to be over the limit, one FILE:FUNCTION a line
(FILE relative to the root, FUNCTION as --list names it). An entry that names no body over the limit fails the check
too, so that an entry goes when its function is split.
"""

import argparse
import os
import re
import sys

LIMIT = 60
DIRS = ("lib", "gtr", "experiments", "bench")
SUFFIXES = (".cpp", ".hpp", ".cpp.in", ".hpp.in")

# --- tokens ---------------------------------------------------------------------------------------------------------

PUNCT = ("...", "->*", "<=>", "::", "->", "&&", "||", "==", "!=", "<=", ">=", "<<", ">>", "++", "--", "+=", "-=",
         "*=", "/=", "%=", "&=", "|=", "^=", ".*", "##")
STRING_PREFIXES = ("u8", "u", "U", "L")
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
NUMBER = re.compile(r"\.?[0-9](?:[eEpP][+-]|'[0-9A-Za-z_]|[0-9A-Za-z_.])*")


class Token:
    __slots__ = ("kind", "text", "line")

    def __init__(self, kind, text, line):
        self.kind, self.text, self.line = kind, text, line  # kind: id, num, str, chr, punct

    def __repr__(self):
        return f"{self.text}@{self.line}"


class ScanError(Exception):
    pass


def _quoted_end(src, i, quote, line):
    """The index after the literal whose opening quote is at src[i]."""
    j = i + 1
    while j < len(src):
        c = src[j]
        if c == "\\":
            j += 2
            continue
        if c == quote:
            return j + 1
        if c == "\n":
            break
        j += 1
    what = "string" if quote == '"' else "character"
    raise ScanError(f"line {line}: unterminated {what} literal")


def tokenize(src):
    """The tokens of C++ source, without comments and preprocessor lines; literals are single tokens."""
    tokens, i, line, n = [], 0, 1, len(src)
    at_line_start = True  # only blanks since the last newline: a '#' here starts a directive
    while i < n:
        c = src[i]
        if c == "\n":
            line, i, at_line_start = line + 1, i + 1, True
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if c == "\\" and src.startswith("\n", i + 1):  # a line continuation
            line, i = line + 1, i + 2
            continue
        if c == "#" and at_line_start:  # a directive, with its continuation lines and comments
            while i < n and src[i] != "\n":
                if src.startswith("\\\n", i):
                    line, i = line + 1, i + 2
                elif src.startswith("/*", i):
                    end = src.find("*/", i + 2)
                    if end < 0:
                        raise ScanError(f"line {line}: unterminated comment")
                    line += src.count("\n", i, end)
                    i = end + 2
                elif src.startswith("//", i):
                    while i < n and src[i] != "\n":
                        i += 1
                else:
                    i += 1
            continue
        at_line_start = False
        if src.startswith("//", i):
            while i < n and src[i] != "\n":
                if src.startswith("\\\n", i):
                    line += 1
                    i += 1
                i += 1
            continue
        if src.startswith("/*", i):
            end = src.find("*/", i + 2)
            if end < 0:
                raise ScanError(f"line {line}: unterminated comment")
            line += src.count("\n", i, end)
            i = end + 2
            continue
        m = IDENT.match(src, i)
        if m:
            word, j = m.group(0), m.end()
            if j < n and src[j] == '"' and word.endswith("R") and word[:-1] in ("",) + STRING_PREFIXES:
                close = src.find("(", j + 1)
                if close < 0 or close - j - 1 > 16:
                    raise ScanError(f"line {line}: bad raw string delimiter")
                end_mark = ")" + src[j + 1:close] + '"'
                end = src.find(end_mark, close + 1)
                if end < 0:
                    raise ScanError(f"line {line}: unterminated raw string")
                end += len(end_mark)
                tokens.append(Token("str", src[i:end], line))
                line += src.count("\n", i, end)
                i = end
                continue
            if j < n and src[j] in "\"'" and word in STRING_PREFIXES:
                end = _quoted_end(src, j, src[j], line)
                tokens.append(Token("str" if src[j] == '"' else "chr", src[i:end], line))
                i = end
                continue
            tokens.append(Token("id", word, line))
            i = j
            continue
        m = NUMBER.match(src, i)
        if m:
            tokens.append(Token("num", m.group(0), line))
            i = m.end()
            continue
        if c in "\"'":
            end = _quoted_end(src, i, c, line)
            tokens.append(Token("str" if c == '"' else "chr", src[i:end], line))
            i = end
            continue
        for p in PUNCT:
            if src.startswith(p, i):
                tokens.append(Token("punct", p, line))
                i += len(p)
                break
        else:
            tokens.append(Token("punct", c, line))
            i += 1
    return tokens


# --- the braces -----------------------------------------------------------------------------------------------------

CONTROL = {"if", "for", "while", "switch", "catch", "requires", "sizeof", "alignof", "decltype", "noexcept",
           "static_assert", "return", "co_return", "co_yield", "throw", "new", "delete", "alignas"}
QUALIFIERS = {"const", "volatile", "noexcept", "override", "final", "mutable", "constexpr", "consteval", "static",
              "&", "&&", "throw"}
# What may stand in a trailing return type or a requires clause between ')' and '{' (groups in () are skipped).
TRAILING = {"::", "<", ">", ">>", ",", "*", "&", "&&", "||", "!", "...", "const", "volatile", "typename"}
CLASS_KEYS = {"class", "struct", "union"}
# Words before '[' after which the '[' opens a lambda's captures (other words make it a subscript).
BEFORE_LAMBDA_WORDS = {"return", "co_return", "co_yield", "throw", "case", "else", "do"}
STATEMENT_END = {";", "{", "}"}


class Body:
    """A function or lambda body: its name, kind ('function' or 'lambda'), and the lines of its braces."""

    __slots__ = ("name", "kind", "first", "last")

    def __init__(self, name, kind, first, last):
        self.name, self.kind, self.first, self.last = name, kind, first, last

    @property
    def lines(self):
        return self.last - self.first + 1

    def __repr__(self):
        return f"{self.kind} {self.name} {self.first}-{self.last}"


class Scanner:
    def __init__(self, tokens):
        self.t = tokens
        self.match = {}  # index of each bracket -> index of its partner
        stack = []
        pairs = {")": "(", "]": "[", "}": "{"}
        for k, tok in enumerate(tokens):
            if tok.kind != "punct":
                continue
            if tok.text in "([{":
                stack.append(k)
            elif tok.text in pairs:
                if not stack or tokens[stack[-1]].text != pairs[tok.text]:
                    raise ScanError(f"line {tok.line}: unbalanced '{tok.text}'")
                self.match[k] = stack.pop()
                self.match[self.match[k]] = k
        if stack:
            raise ScanError(f"line {tokens[stack[-1]].line}: '{tokens[stack[-1]].text}' never closed")

    def text(self, k):
        return self.t[k].text if 0 <= k < len(self.t) else ""

    def is_punct(self, k, text):
        return 0 <= k < len(self.t) and self.t[k].kind == "punct" and self.t[k].text == text

    def is_word(self, k):
        return 0 <= k < len(self.t) and self.t[k].kind == "id"

    def skip_angles_back(self, k):
        """From a '>' (or '>>') at k, the index before its matching '<'; None when it does not balance."""
        depth = 0
        while k >= 0:
            tok = self.t[k]
            if tok.kind == "punct":
                if tok.text in (")", "]"):
                    k = self.match[k]
                elif tok.text == ">":
                    depth += 1
                elif tok.text == ">>":
                    depth += 2
                elif tok.text == "<":
                    depth -= 1
                    if depth == 0:
                        return k - 1
                elif tok.text in (";", "{", "}", "(", "["):
                    return None
            k -= 1
        return None

    def skip_trailing(self, k):
        """From the token before a '{': the index before a trailing return type ('-> T') or a requires clause, or
        k itself when there is neither."""
        j = k
        while j >= 0:
            tok = self.t[j]
            if tok.kind == "punct" and tok.text == ")":
                j = self.match[j] - 1
                continue
            if (tok.kind == "punct" and tok.text == "->" and self.text(j - 1) != "operator") or \
                    (tok.kind == "id" and tok.text == "requires"):
                # only after a parameter list: a requires clause before a declaration is no trailing part
                return j - 1 if self.is_punct(self.skip_qualifiers(j - 1), ")") else k
            if tok.kind in ("id", "num") or (tok.kind == "punct" and tok.text in TRAILING):
                j -= 1
                continue
            return k
        return k

    def skip_qualifiers(self, k):
        """The index before the qualifiers (const, noexcept(...), [[...]] ...) that end a declarator at k."""
        while k >= 0:
            if self.t[k].kind == "id" and self.t[k].text in QUALIFIERS or self.text(k) in ("&", "&&"):
                k -= 1
            elif self.is_punct(k, ")") and self.text(self.match[k] - 1) in ("noexcept", "throw"):
                k = self.match[k] - 2
            elif self.is_punct(k, "]") and self.is_punct(k - 1, "]") and self.is_punct(self.match[k], "["):
                k = self.match[k - 1] - 1  # an attribute [[...]]
            else:
                return k

    def declarator_end(self, k):
        """k, the token before a '{', moved past a trailing return type, requires clause and qualifiers."""
        return self.skip_qualifiers(self.skip_trailing(k))

    def lambda_captures(self, close):
        """Whether the ']' at close ends a lambda's captures (not a subscript, an array bound or an attribute)."""
        if not self.is_punct(close, "]"):
            return False
        open_ = self.match[close]
        if self.is_punct(open_ - 1, "[") or self.is_punct(close - 1, "]"):
            return False  # [[attribute]]
        before = open_ - 1
        if before < 0:
            return True
        tok = self.t[before]
        if tok.kind in ("num", "str", "chr"):
            return False
        if tok.kind == "id":
            return tok.text in BEFORE_LAMBDA_WORDS
        return tok.text not in (")", "]")

    def function_name(self, paren):
        """The name before the parameter list opening at paren: f, A::f, A<T>::f, ~A, operator(), operator==,
        operator T."""
        k = paren - 1
        if self.text(k - 2) == "operator" and self.text(k - 1) + self.text(k) in ("()", "[]"):
            k, name = k - 2, "operator" + self.text(k - 1) + self.text(k)
        elif self.text(k - 1) == "operator":
            k, name = k - 1, "operator" + (" " if self.is_word(k) else "") + self.text(k)
        else:
            if self.text(k) in (">", ">>"):  # f<int>(...)
                k = self.skip_angles_back(k)
            if k is None or not self.is_word(k):
                return "?"
            name = self.text(k)
            if self.is_punct(k - 1, "~"):
                k, name = k - 1, "~" + name
        parts = [name]
        while self.is_punct(k - 1, "::"):
            k -= 2
            if self.text(k) in (">", ">>"):
                k = self.skip_angles_back(k)
            if k is None or not self.is_word(k):
                break
            parts.append(self.text(k))
        return "::".join(reversed(parts))

    def member_initializers(self, k):
        """When k ends a constructor's member initialiser list (': a_(x), b_{y}'), the index of the ')' that closes
        the constructor's parameters; else None."""
        while True:
            if self.is_punct(k, "..."):
                k -= 1
            if not (self.is_punct(k, ")") or self.is_punct(k, "}")):
                return None
            k = self.match[k] - 1
            if self.text(k) in (">", ">>"):  # Base<T>(x)
                k = self.skip_angles_back(k)
                if k is None:
                    return None
            if not self.is_word(k):
                return None
            while self.is_punct(k - 1, "::") and self.is_word(k - 2):
                k -= 2
            k -= 1
            if self.is_punct(k, ","):
                k -= 1
                continue
            if not self.is_punct(k, ":"):
                return None
            end = self.skip_qualifiers(k - 1)
            return end if self.is_punct(end, ")") else None

    def classify(self, brace):
        """('function', name) or ('lambda', name) for a body's '{', ('class', name) for a class body, else
        ('other', None)."""
        k = brace - 1
        if k < 0:
            return "other", None
        ctor = self.member_initializers(k)
        if ctor is not None:
            return "function", self.function_name(self.match[ctor])
        end = self.declarator_end(k)
        if self.lambda_captures(end):
            return "lambda", self.lambda_name(self.match[end])
        if self.is_punct(end, ")"):
            paren = self.match[end]
            before = paren - 1
            if self.text(before) in (">", ">>"):  # a template lambda []<class T>(T x) or f<int>(x)
                angle = self.skip_angles_back(before)
                if angle is not None and self.lambda_captures(angle):
                    return "lambda", self.lambda_name(self.match[angle])
            if self.lambda_captures(before):
                return "lambda", self.lambda_name(self.match[before])
            word = self.text(before)
            if word in CONTROL or (word == "constexpr" and self.text(before - 1) == "if"):
                return "other", None
            if self.is_word(before) or self.text(before) in (">", ">>", ")") or self.text(before - 1) == "operator":
                return "function", self.function_name(paren)
            return "other", None
        return self.class_head(brace)

    def lambda_name(self, open_):
        """The variable a lambda is assigned to (auto name = [..]), else 'lambda'."""
        if self.is_punct(open_ - 1, "=") and self.is_word(open_ - 2):
            return self.text(open_ - 2)
        return "lambda"

    def class_head(self, brace):
        """('class', name) when the statement before brace is a class head (not 'enum class'), else ('other', None)."""
        start = brace - 1
        while start >= 0 and not (self.t[start].kind == "punct" and self.t[start].text in STATEMENT_END):
            if self.t[start].kind == "punct" and self.t[start].text in (")", "]"):
                start = self.match[start]
            start -= 1
        depth = 0
        for q in range(start + 1, brace):
            tok = self.t[q]
            if tok.kind == "punct":
                if tok.text == "<":
                    depth += 1
                elif tok.text in (">", ">>"):
                    depth = max(0, depth - len(tok.text))
                elif tok.text == "=" and depth == 0:
                    return "other", None
            elif tok.kind == "id" and depth == 0 and tok.text in CLASS_KEYS and self.text(q - 1) != "enum":
                name = q + 1
                while True:  # past alignas(...) and [[attributes]]
                    if self.text(name) == "alignas" and self.is_punct(name + 1, "("):
                        name = self.match[name + 1] + 1
                    elif self.is_punct(name, "["):
                        name = self.match[name] + 1
                    else:
                        break
                return "class", self.text(name) if name < brace and self.is_word(name) else "(anonymous)"
        return "other", None

    def bodies(self):
        """Every function and lambda body, with names qualified by the classes and functions around it."""
        out, scopes = [], []  # scopes: (index of '}', name component or None)
        for k, tok in enumerate(self.t):
            if tok.kind != "punct":
                continue
            while scopes and scopes[-1][0] < k:
                scopes.pop()
            if tok.text != "{":
                continue
            kind, name = self.classify(k)
            close = self.match[k]
            if kind in ("function", "lambda"):
                full = "::".join([s[1] for s in scopes if s[1]] + [name])
                out.append(Body(full, kind, tok.line, self.t[close].line))
            scopes.append((close, name if kind in ("function", "lambda", "class") else None))
        return out


def bodies_of(src):
    return Scanner(tokenize(src)).bodies()


# --- the check ------------------------------------------------------------------------------------------------------


def source_files(root, tops=DIRS):
    """The sources under root's folders tops, skipping build trees (folders with a CMakeCache.txt or CMakeFiles)."""
    for d in tops:
        for here, dirs, files in os.walk(os.path.join(root, d)):
            dirs[:] = sorted(x for x in dirs if x != "CMakeFiles" and
                             not os.path.exists(os.path.join(here, x, "CMakeCache.txt")))
            for f in sorted(files):
                if f.endswith(SUFFIXES):
                    path = os.path.join(here, f)
                    yield os.path.relpath(path, root).replace(os.sep, "/"), path


def over_limit(files, limit):
    """(file, body) for each body over limit lines, from (name, text) pairs; ScanError names the file."""
    found = []
    for name, text in files:
        try:
            found += [(name, b) for b in bodies_of(text) if b.lines > limit]
        except ScanError as e:
            raise ScanError(f"{name}: {e}") from None
    return found


def read_allow(text, source):
    """The FILE:FUNCTION entries of an allow-list (blank lines and '#' comments skipped), with their lines."""
    entries = []
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if ":" not in line or line.startswith(":") or line.endswith(":"):
            raise ScanError(f"{source}:{n}: '{raw.strip()}' is not FILE:FUNCTION")
        f, fn = line.split(":", 1)
        entries.append((f.strip(), fn.strip(), n))
    return entries


def check(found, allow, allow_source, limit):
    """The failures: bodies over limit not allowed, and allow entries naming no body over limit."""
    problems = []
    allowed = {(f, fn) for f, fn, _ in allow}
    for f, b in found:
        if (f, b.name) not in allowed:
            problems.append(f"{f}:{b.first}: {b.kind} {b.name} is {b.lines} lines (at most {limit})")
    present = {(f, b.name) for f, b in found}
    for f, fn, n in allow:
        if (f, fn) not in present:
            problems.append(f"{allow_source}:{n}: {f}:{fn} is allowed but no longer over {limit} lines (or gone): "
                            "remove the entry")
    return problems


# --- the self-test --------------------------------------------------------------------------------------------------

SAMPLE = r'''#include <string>  // {
#define NOTHING {
namespace outer { namespace {
/* a comment with } and {
   over lines */
struct Point {
    int x{0}, y = {1};
    int sum() const noexcept { return x + y; }
    Point() : x{1}, y(2) {
    }
    bool operator==(const Point&) const = default;
    auto operator()(int a) -> std::pair<int, int> {
        return {a, a};
    }
};
enum class Colour : int { red, green };
int f(int a) {
    const char* s = "}{\"}";
    char c = '{', q = '\'';
    long n = 1'000'000;
    const char* raw = R"x(
        } ) " }
    )x";
    if (a > 0) {
        for (int i = 0; i < a; ++i) {
            a += i;
        }
    } else {
        while (a < 0) { ++a; }
    }
    auto twice = [&](int v) mutable -> int {
        return 2 * v;
    };
    std::vector<int> v{1, 2};
    g({1, 2}, [] {
        return 0;
    });
    int arr[2]{3, 4};
    try {
        switch (a) { case 1: { break; } }
    } catch (const std::exception& e) {
    }
    if constexpr (requires { a.f(); }) { a.f(); }
    auto tl = []<class T>(T t) { return t; };
    return twice(a) + arr[0] + v[0];
}
template <class T>
T g(T t) requires std::is_integral_v<T> {
    struct Local {
        void m() {
        }
    };
    return t;
}
class Holder : public Base<int> {
public:
    Holder(int a) noexcept(true) : Base<int>(a), cb_([](int) { return 1; }) {}
    ~Holder() {}
};
}  // namespace
int Point2::area() const & {
    return 0;
}
}  // namespace outer
extern "C" {
int c_fn(void) { return 0; }
}
'''

SAMPLE_BODIES = [
    ("function", "Point::sum", 8, 8), ("function", "Point::Point", 9, 10),
    ("function", "Point::operator()", 12, 14), ("function", "f", 17, 46), ("lambda", "f::twice", 31, 33),
    ("lambda", "f::lambda", 35, 37), ("lambda", "f::tl", 44, 44), ("function", "g", 48, 54),
    ("function", "g::Local::m", 50, 51), ("lambda", "Holder::lambda", 57, 57), ("function", "Holder::Holder", 57, 57),
    ("function", "Holder::~Holder", 58, 58), ("function", "Point2::area", 61, 63), ("function", "c_fn", 66, 66),
]


def body_of_lines(name, n):
    """A function whose braces span n lines."""
    return f"void {name}() {{\n" + "    x();\n" * (n - 2) + "}\n"


def self_test():
    failures = []

    def expect(what, got, want):
        if got != want:
            failures.append(f"{what}: got {got!r}, want {want!r}")

    got = [(b.kind, b.name, b.first, b.last) for b in bodies_of(SAMPLE)]
    expect("bodies of the sample", got, SAMPLE_BODIES)
    expect("lengths", [b.lines for b in bodies_of(body_of_lines("a", LIMIT) + body_of_lines("b", LIMIT + 1))],
           [LIMIT, LIMIT + 1])
    for bad in ('void f() { "unterminated }\n', "void f() {\n", "void f() { /* }\n", 'auto s = R"x(never)";\n'):
        try:
            bodies_of(bad)
            failures.append(f"no error for {bad!r}")
        except ScanError:
            pass

    files = [("a.cpp", body_of_lines("long_one", LIMIT + 1) + body_of_lines("short_one", LIMIT)),
             ("b.hpp", body_of_lines("allowed", LIMIT + 5))]
    found = over_limit(files, LIMIT)
    expect("over the limit", [(f, b.name, b.lines) for f, b in found],
           [("a.cpp", "long_one", LIMIT + 1), ("b.hpp", "allowed", LIMIT + 5)])
    allow = read_allow("# known\nb.hpp:allowed\n\na.cpp:short_one  # split\nc.cpp:gone\n", "allow.txt")
    expect("allow entries", allow, [("b.hpp", "allowed", 2), ("a.cpp", "short_one", 4), ("c.cpp", "gone", 5)])
    expect("problems", check(found, allow, "allow.txt", LIMIT), [
        f"a.cpp:1: function long_one is {LIMIT + 1} lines (at most {LIMIT})",
        f"allow.txt:4: a.cpp:short_one is allowed but no longer over {LIMIT} lines (or gone): remove the entry",
        f"allow.txt:5: c.cpp:gone is allowed but no longer over {LIMIT} lines (or gone): remove the entry",
    ])
    expect("no problems", check(found, read_allow("a.cpp:long_one\nb.hpp:allowed\n", "x"), "x", LIMIT), [])
    try:
        read_allow("just_a_name\n", "allow.txt")
        failures.append("no error for an entry without FILE:")
    except ScanError:
        pass

    for f in failures:
        print("self-test:", f, file=sys.stderr)
    print(f"self-test: {'FAILED' if failures else 'passed'}")
    return 1 if failures else 0


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", default=os.path.dirname(here), help="the source tree (default: this file's ../)")
    p.add_argument("--allow", default=os.path.join(here, "function_lengths_allow.txt"), help="the allow-list")
    p.add_argument("--limit", type=int, default=LIMIT, help=f"the most lines a body may span (default {LIMIT})")
    p.add_argument("--list", action="store_true", help="list every body over the limit and exit 0")
    p.add_argument("--self-test", action="store_true", help="check the scanner on inline samples")
    a = p.parse_args()
    if a.self_test:
        return self_test()
    try:
        files = []
        for name, path in source_files(a.root):
            with open(path, encoding="utf-8") as fh:
                files.append((name, fh.read()))
        if not files:
            raise ScanError(f"no sources under {a.root} ({', '.join(DIRS)})")
        found = over_limit(files, a.limit)
        if a.list:
            for f, b in sorted(found, key=lambda fb: -fb[1].lines):
                print(f"{b.lines:4d} {f}:{b.first} {f}:{b.name} ({b.kind})")
            return 0
        allow_source = os.path.relpath(a.allow, a.root)
        if allow_source.startswith(".."):
            allow_source = a.allow
        with open(a.allow, encoding="utf-8") as fh:
            allow = read_allow(fh.read(), allow_source)
    except (ScanError, OSError) as e:
        print(f"function_lengths: {e}", file=sys.stderr)
        return 2
    problems = check(found, allow, allow_source, a.limit)
    for line in problems:
        print(line, file=sys.stderr)
    print(f"function_lengths: {len(files)} files, {len(found)} bodies over {a.limit} lines, {len(allow)} allowed, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
