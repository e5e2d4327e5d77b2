#!/usr/bin/env python3
"""Every reference to a document, and to a section of it, resolves.

Code comments and docs cite a section by file and anchor, `<file>.md#<anchor>`, the file
repository-relative or relative to the citing file (common/formats/README.md#writing-files).
Markdown documents use relative links, `[text](<file>.md#<anchor>)` or `[text](#<anchor>)`.
A renamed or removed heading leaves such references pointing nowhere (issue 30); this finds
them all:

- in every tracked text file, each `<file>.md#<anchor>`: the file must exist and have a heading
  whose GitHub anchor is `anchor`;
- in every tracked .md file, each relative Markdown link (outside code blocks): the target
  must exist, and for a .md target with `#anchor`, the anchor must be one of its headings';
- in every tracked text file, each document named without a section (`common/README.md`):
  the file must exist (a document the repository does not hold is no reference for a
  user who clones it alone); installed paths (`share/doc/...`) pass;
- the old citation by title (a README and a quoted heading) is refused: cite
  `<file>.md#<anchor>`.

Anchors follow GitHub's rule: the heading's text (inline code, emphasis and links reduced to
their text), lower-cased, every character that is not a letter, digit, '_', '-' or space
dropped, spaces turned into '-'; a repeated anchor gets '-1', '-2', ...

Before checking the tree it checks itself: the anchor rule on known headings, and a temporary
copy of the tree's documents and citing files with a renamed heading must fail.
Usage: doc_citations_test.py SOURCE_DIR [--no-self-test]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP_DIRS = re.compile(r'^(build.*|\.git|node_modules)$')
MAX_BYTES = 1_000_000
# <file>.md#<anchor> not inside a URL (no '://' or '/' glued before it); the path may be bare.
CITATION = re.compile(r'(?<![\w/.:-])((?:\.\.?/)*(?:[\w.-]+/)*[\w.-]+\.md)#([\w-]+)')
# A document named without a section (`common/README.md`): the file must exist. An installed
# path (`share/doc/h4cal/README.md`) is not in the tree and is passed over.
DOCUMENT = re.compile(r'(?<![\w/.:-])((?:\.\.?/)*(?:[\w.-]+/)*[\w.-]+\.md)(?![\w#-])')
# [text](target) or ![alt](target), target without spaces, an optional "title".
LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
OLD_STYLE = re.compile(r'\b[\w./-]*README(?:\.md)?[,:]?\s+(?:sections?\s+)?"[A-Z][^"\n]*"')
FENCE = re.compile(r'^\s*(```|~~~)')


def slug(heading):
    """GitHub's anchor for a heading's Markdown text."""
    text = re.sub(r'!?\[([^\]]*)\]\([^)]*\)', r'\1', heading)  # links and images: their text
    text = re.sub(r'<[^>]+>', '', text)  # inline HTML
    text = text.strip().lower()
    text = re.sub(r'[^\w\- ]', '', text)
    return text.replace(' ', '-')


def prose_lines(text):
    """(line number, line) of a Markdown text outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(text.split('\n'), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def anchors_of(text):
    found, seen = set(), {}
    for _, line in prose_lines(text):
        m = re.match(r'^ {0,3}#{1,6}\s+(.*?)\s*#*\s*$', line)
        if m:
            base = slug(m.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f'{base}-{n}')
        for m in re.finditer(r'<a\s+(?:name|id)="([^"]+)"', line):
            found.add(m.group(1))
    return found


class Tree:
    def __init__(self, root, tracked=True):
        self.root = os.path.realpath(root)
        self.tracked = tracked  # list the files with git (a scratch copy is walked)
        self._anchors = {}
        self._texts = {}

    def files(self):
        try:
            if not self.tracked:
                raise OSError('walk the copy')
            out = subprocess.run(['git', '-C', self.root, 'ls-files', '-z'], check=True,
                                 capture_output=True).stdout.decode()
            names = [n for n in out.split('\0') if n]
            if names:
                return sorted(n for n in names if os.path.isfile(os.path.join(self.root, n)))
        except (OSError, subprocess.CalledProcessError):
            pass
        names = []
        for folder, dirs, files in os.walk(self.root):
            dirs[:] = [d for d in dirs if not SKIP_DIRS.match(d)]
            for name in files:
                names.append(os.path.relpath(os.path.join(folder, name), self.root))
        return sorted(names)

    def read(self, name):
        if name not in self._texts:
            path = os.path.join(self.root, name)
            try:
                if os.path.getsize(path) > MAX_BYTES:
                    raise OSError('too large')
                with open(path, encoding='utf-8') as f:
                    self._texts[name] = f.read()
            except (UnicodeDecodeError, OSError):
                self._texts[name] = None
        return self._texts[name]

    def anchors(self, name):
        if name not in self._anchors:
            text = self.read(name)
            self._anchors[name] = None if text is None else anchors_of(text)
        return self._anchors[name]

    def existing(self, candidates):
        """The first candidate (repository-relative) that exists inside the tree."""
        for c in candidates:
            path = os.path.normpath(c)
            if not path.startswith('..') and os.path.exists(os.path.join(self.root, path)):
                return path
        return None


def check_anchor(tree, target, anchor, where, what):
    anchors = tree.anchors(target)
    if anchors is not None and anchor not in anchors:
        return f'{where}: {what}: {target} has no heading with anchor #{anchor}'
    return None


def check(tree):
    """(failures, code citations, Markdown links) of the tree."""
    failures, citations, links, documents = [], 0, 0, 0
    for name in tree.files():
        text = tree.read(name)
        if text is None:
            continue
        folder = os.path.dirname(name)
        is_md = name.endswith('.md')
        if not is_md and '.md' not in text and 'README' not in text:
            continue
        lines = list(prose_lines(text)) if is_md else list(enumerate(text.split('\n'), 1))
        for number, line in lines:
            if not is_md and '.md' not in line and 'README' not in line:
                continue
            where = f'{name}:{number}'
            for m in OLD_STYLE.finditer(line):
                failures.append(f'{where}: {m.group(0)!r}: cite a section as <file>.md#<anchor>')
            scan = line
            if is_md:
                for m in LINK.finditer(line):
                    links += 1
                    failure = check_link(tree, name, m.group(1), where)
                    if failure:
                        failures.append(failure)
                scan = LINK.sub('', line)
            for m in DOCUMENT.finditer(scan):
                path = m.group(1)
                if 'share/doc/' in path:
                    continue
                documents += 1
                if tree.existing([path, os.path.join(folder, path)]) is None:
                    failures.append(f'{where}: {path}: no such document in the repository')
            for m in CITATION.finditer(scan):
                citations += 1
                path, anchor = m.group(1), m.group(2)
                target = tree.existing([path, os.path.join(folder, path)])
                if target is None:
                    failures.append(f'{where}: {path}#{anchor}: no such file')
                    continue
                failure = check_anchor(tree, target, anchor, where, f'{path}#{anchor}')
                if failure:
                    failures.append(failure)
    return failures, citations, links, documents


def check_link(tree, name, target, where):
    if re.match(r'^[a-z][a-z0-9+.-]*:', target, re.I):  # http:, https:, mailto:
        return None
    path, _, anchor = target.partition('#')
    if path:
        base = '' if path.startswith('/') else os.path.dirname(name)
        resolved = tree.existing([os.path.join(base, path.lstrip('/'))])
        if resolved is None:
            return f'{where}: link ({target}): no such file'
    else:
        resolved = name
    if anchor and resolved.endswith('.md'):
        return check_anchor(tree, resolved, anchor, where, f'link ({target})')
    return None


def self_test(root):
    """The checker fails where it must; returns the problems with the checker itself."""
    problems = []
    known = {
        'The verdict of `h4cal identify`: what it means and what to do':
            'the-verdict-of-h4cal-identify-what-it-means-and-what-to-do',
        'h4cal — vision-based kinematic calibration of H4 parallel robots':
            'h4cal--vision-based-kinematic-calibration-of-h4-parallel-robots',
        "Board poses through a real camera's image (measured)":
            'board-poses-through-a-real-cameras-image-measured',
        'Board corners: CSV': 'board-corners-csv',
        'Paired dataset: CSV': 'paired-dataset-csv',
        'What the controller receives: `H4_ROBOT_TARGET` (`robot_target_t`)':
            'what-the-controller-receives-h4_robot_target-robot_target_t',
        'See [the docs](docs/x' '.md) *now*': 'see-the-docs-now',
    }
    for heading, expected in known.items():
        if slug(heading) != expected:
            problems.append(f'slug({heading!r}) = {slug(heading)!r}, GitHub says {expected!r}')
    if anchors_of('# A\n## A\n```\n# not a heading\n```\n### A\n') != {'a', 'a-1', 'a-2'}:
        problems.append('duplicate headings or fenced code handled wrongly')

    # A copy of the documents and of every file citing one; then one heading renamed.
    tree = Tree(root)
    with tempfile.TemporaryDirectory() as scratch:
        for name in tree.files():
            text = tree.read(name)
            if text is None or not (name.endswith('.md') or '.md#' in text):
                continue
            os.makedirs(os.path.join(scratch, os.path.dirname(name)), exist_ok=True)
            shutil.copyfile(os.path.join(tree.root, name), os.path.join(scratch, name))
        before, _, _, _ = check(Tree(scratch, tracked=False))
        readme = os.path.join(scratch, 'README.md')
        with open(readme, encoding='utf-8') as f:
            text = f.read()
        renamed = text.replace('\n## Using h4cal\n', '\n## Using the h4cal program\n', 1)
        if renamed == text:
            problems.append('self-test: README.md has no "## Using h4cal" heading to rename')
            return problems
        with open(readme, 'w', encoding='utf-8') as f:
            f.write(renamed)
        after, _, _, _ = check(Tree(scratch, tracked=False))
        broken = [f for f in after if f not in before]
        if not any('#using-h4cal' in f and not f.startswith('README.md') for f in broken):
            problems.append('self-test: renaming README.md "## Using h4cal" broke no citation '
                            'in another file')
        if not any(f.startswith('README.md:') and 'link (#using-h4cal)' in f for f in broken):
            problems.append("self-test: renaming it broke none of README.md's own links")
        broken_doc = 'broken' '.md'
        with open(os.path.join(scratch, broken_doc), 'w', encoding='utf-8') as f:
            f.write('# Broken\n\n[gone](docs/no-such-file' '.md) `README.md ' + '"Using h4cal"`\n'
                    'Old: docs/results.md' + '#no-such-heading\nAs style' '.md item 7 says\n')
        last, _, _, _ = check(Tree(scratch, tracked=False))
        for expected in ('link (docs/no-such-file' '.md): no such file',
                         'style' '.md: no such document',
                         'cite a section as', '#no-such-heading'):
            if not any(f.startswith(broken_doc + ':') and expected in f for f in last):
                problems.append(f'self-test: no failure "{expected}" on {broken_doc}')
    return problems


def main():
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    root = os.path.realpath(args[0] if args else '.')
    if '--no-self-test' not in sys.argv:
        problems = self_test(root)
        if problems:
            print('\n'.join(problems))
            print('FAIL: the checker itself is wrong')
            return 1
        print('self-test: a renamed heading and a missing file are caught')
    failures, citations, links, documents = check(Tree(root))
    print('\n'.join(failures))
    print(f'{citations} <file>.md#<anchor> citations, {links} Markdown links, '
          f'{documents} documents named, {len(failures)} pointing nowhere')
    # A checker that finds nothing checks nothing: the tree cites documents by the dozen.
    if citations < 50 or links < 50:
        print('FAIL: fewer than 50 citations or links found; the patterns no longer match them')
        return 1
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
