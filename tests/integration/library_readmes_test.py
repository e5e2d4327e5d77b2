#!/usr/bin/env python3
"""Each library folder has a README that names each of its headers, and none that is gone.

host/<library>/README.md lists the headers other folders call and the internal ones
(issue 30: which headers of a library are its interface was said nowhere). A header added
without a line there, or a line left for a removed one, fails here. Before checking the tree
it checks itself on a temporary folder with one header missing from its README and one
README line naming no file.
Usage: library_readmes_test.py SOURCE_DIR
"""
import os
import re
import sys
import tempfile

HEADER = re.compile(r'`([\w]+\.h)`')


def check_folder(folder):
    """Failures of one library folder: a README.md naming each header, and no other."""
    if not os.path.isfile(os.path.join(folder, 'README.md')):
        return [f'{folder}: a library folder without a README.md']
    with open(os.path.join(folder, 'README.md'), encoding='utf-8') as f:
        named = set(HEADER.findall(f.read()))
    present = {n for n in os.listdir(folder) if n.endswith('.h')}
    where = os.path.join(folder, 'README.md')
    return ([f'{where}: {h} is not named' for h in sorted(present - named)] +
            [f'{where}: {h} is named but not in the folder' for h in sorted(named - present)])


# The benchmarks' folders are programs, not a library (docs/development.md describes them).
NOT_LIBRARIES = {'bench'}


def library_folders(root):
    """Every folder of host/ and firmware/ that holds headers: each is a library.

    common/README.md and common/formats/README.md are the conventions and the file formats,
    not a library's map.
    """
    for top in ('host', 'firmware'):
        base = os.path.join(root, top)
        for name in sorted(os.listdir(base)) if os.path.isdir(base) else []:
            folder = os.path.join(base, name)
            if name not in NOT_LIBRARIES and os.path.isdir(folder) and any(
                    n.endswith('.h') for n in os.listdir(folder)):
                yield folder


def self_test():
    with tempfile.TemporaryDirectory() as folder:
        for name in ('kept.h', 'unnamed.h'):
            open(os.path.join(folder, name), 'w').close()
        with open(os.path.join(folder, 'README.md'), 'w') as f:
            f.write('| `kept.h` | here |\n| `removed.h` | gone |\n')
        failures = check_folder(folder)
    expected = ('unnamed.h is not named', 'removed.h is named but not in the folder')
    return [f'self-test: no failure "{e}"' for e in expected
            if not any(e in f for f in failures)]


def main():
    problems = self_test()
    if problems:
        print('\n'.join(problems) + '\nFAIL: the checker itself is wrong')
        return 1
    folders = list(library_folders(os.path.realpath(sys.argv[1] if len(sys.argv) > 1 else '.')))
    failures = [f for folder in folders for f in check_folder(folder)]
    print('\n'.join(failures))
    print(f'{len(folders)} library READMEs checked, {len(failures)} failures')
    if not folders:
        print('FAIL: no library README found')
        return 1
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
