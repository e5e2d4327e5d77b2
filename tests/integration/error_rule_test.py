#!/usr/bin/env python3
"""The rule for exception types (docs/architecture.md#errors-one-idiom-for-checking-one-rule-for-exceptions).

The code of common/, host/, firmware/, messages/ and examples/ throws std::invalid_argument
(a caller's mistake), h4::FormatError (a file's content) or std::runtime_error (the world,
also through the SystemError helper that makes one), plus two protocol exceptions of the
libraries it talks to: CLI::RuntimeError (a command's exit code, common/cli/subcommand.h)
and nlopt::forced_stop (stops NLopt from inside its callback). `throw;` rethrows. A message
that names an option (it starts with "--") is a caller's mistake: thrown as
std::runtime_error it fails. Comments and string literals are not read as code.

Usage: error_rule_test.py SOURCE_DIR [--self-test]
"""
import pathlib
import re
import sys

FOLDERS = ("common", "host", "firmware", "messages", "examples")
ALLOWED = {"std::invalid_argument", "std::runtime_error", "FormatError", "h4::FormatError",
           "CLI::RuntimeError", "nlopt::forced_stop", "SystemError"}
THROW = re.compile(r"(?<![\w.])throw\b\s*([A-Za-z_][\w:]*)?")
OPTION_AS_WORLD = re.compile(
    r'(?<![\w.])throw\s+std::runtime_error\(\s*(?:fmt::format\(\s*)?"--')
STRING = re.compile(r'"(?:[^"\\]|\\.)*"')
COMMENT_OR_STRING = re.compile(r'//[^\n]*|/\*.*?\*/|"(?:[^"\\\n]|\\.)*"', re.S)


def code_of(text):
    """`text` without its comments (their line breaks kept); string literals kept."""
    def blank(m):
        found = m.group(0)
        return found if found.startswith('"') else re.sub(r"[^\n]", " ", found)
    return COMMENT_OR_STRING.sub(blank, text)


def line_of(text, position):
    return text.count("\n", 0, position) + 1


def problems_in(path, text):
    """(the problems of one file, its throw expressions counted)."""
    code = code_of(text)
    without_strings = STRING.sub(lambda m: '"' + " " * (len(m.group(0)) - 2) + '"', code)
    found, count = [], 0
    for m in THROW.finditer(without_strings):
        count += 1
        if m.group(1) is not None and m.group(1) not in ALLOWED:  # "throw;" rethrows
            found.append(f"{path}:{line_of(code, m.start())}: throws {m.group(1)}, "
                         "not one of the rule's types")
    for m in OPTION_AS_WORLD.finditer(code):
        found.append(f"{path}:{line_of(code, m.start())}: an option's mistake thrown as "
                     "std::runtime_error (use std::invalid_argument)")
    return found, count


def check_tree(root):
    problems, count = [], 0
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".cpp", ".h") or not path.is_file():
                continue
            found, n = problems_in(path.relative_to(root), path.read_text(errors="replace"))
            problems += found
            count += n
    return problems, count


def self_test():
    """The check must fail on each kind of breach and pass the allowed forms."""
    bad = ('void f() { throw std::out_of_range("x"); }\n'
           'void g() { throw std::runtime_error("--frames 0: expected 1..100"); }\n'
           'void h() {\n  throw std::runtime_error(\n      fmt::format("--pose: got {}", 3));\n}\n')
    good = ('void f() { throw std::invalid_argument("--frames 0"); }  // throw std::exception\n'
            'void g() { try { h(); } catch (...) { throw; } }\n'
            'const char* s = "throw std::logic_error";  /* throw std::exception */\n')
    bad_found, _ = problems_in("bad.cpp", bad)
    good_found, good_count = problems_in("good.cpp", good)
    ok = len(bad_found) == 3 and not good_found and good_count == 2
    print(f"self-test: {'passed' if ok else 'FAILED'} ({bad_found}, {good_found})")
    return ok


def main():
    root = pathlib.Path(sys.argv[1])
    if not self_test():
        return 1
    problems, count = check_tree(root)
    for p in problems:
        print("FAIL:", p)
    if problems:
        return 1
    print(f"error rule: {count} throw expressions checked, none off the rule")
    return 0


if __name__ == "__main__":
    sys.exit(main())
