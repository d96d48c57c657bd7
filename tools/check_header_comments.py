#!/usr/bin/env python3
"""Flags header comments over three lines directly above a declaration.

  tools/check_header_comments.py [--except GLOB]... PATH...

PATH: header files or folders (searched for *.hpp). A flagged block is a
run of more than three `//` lines followed at once by code at namespace or
class scope; a file's opening comment and comments inside function bodies
are not declarations' and pass. Prints FILE:LINE for each; exit 1 if any.
"""
import fnmatch
import os
import re
import sys

MAX_LINES = 3
SCOPE_WORDS = re.compile(r'\b(namespace|class|struct|union|enum)\b|^extern\b')
FUNCTION_HEAD = re.compile(r'\)\s*(const|noexcept|override|final|mutable|\s)*$')


def strip_code(line):
    """The line without string and char literals and its // comment."""
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    at = line.find('//')
    return line if at < 0 else line[:at]


def flagged(path):
    lines = open(path, encoding='utf-8').read().split('\n')
    out = []
    scopes = []      # per open brace: True for namespace/class scope
    pending = ''     # code since the last ; { or }
    i = 0
    seen_code = False
    while i < len(lines):
        stripped = lines[i].strip()
        if stripped.startswith('//'):
            j = i
            while j < len(lines) and lines[j].strip().startswith('//'):
                j += 1
            after = lines[j].strip() if j < len(lines) else ''
            in_body = scopes and not scopes[-1]
            declaration = after and not after.startswith(('#', '}', '//')) and after not in ('public:', 'private:', 'protected:')
            if seen_code and not in_body and declaration and j - i > MAX_LINES:
                out.append((i + 1, j - i, after))
            i = j
            continue
        if stripped and not stripped.startswith('#'):
            seen_code = True
        for ch in strip_code(lines[i]):
            if ch == '{':
                # A function body's brace follows its parameter list (or a
                # constructor's initializers, a trailing return type);
                # anything else is a namespace or class scope, or braces of
                # an enum or initializer, harmless. Inside a body, all is.
                head = pending.strip()
                body = (scopes and not scopes[-1]) or (not SCOPE_WORDS.search(head) and (FUNCTION_HEAD.search(head) or '->' in head))
                scopes.append(not body)
                pending = ''
            elif ch == '}':
                if scopes:
                    scopes.pop()
                pending = ''
            elif ch == ';':
                pending = ''
            else:
                pending += ch
        pending += ' '
        i += 1
    return out


def main(argv):
    excepts, paths = [], []
    it = iter(argv)
    for a in it:
        if a == '--except':
            excepts.append(next(it))
        else:
            paths.append(a)
    files = []
    for p in paths:
        if os.path.isdir(p):
            for root, _, names in os.walk(p):
                files += [os.path.join(root, n) for n in names if n.endswith('.hpp')]
        else:
            files.append(p)
    bad = 0
    for f in sorted(files):
        if any(fnmatch.fnmatch(os.path.basename(f), g) for g in excepts):
            continue
        for line, n, after in flagged(f):
            print('%s:%d: %d comment lines above a declaration (at most %d): %s' % (f, line, n, MAX_LINES, after[:60]))
            bad += 1
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
