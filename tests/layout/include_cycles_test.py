#!/usr/bin/env python3
"""scripts/include_cycles.py finds cycles, and only cycles: on small trees written to a temporary
folder, two headers that include each other, a header and the source of another component that
include each other's component, and a diamond of includes that is no cycle."""

import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "include_cycles.py")


def write_tree(root, files):
    for path, text in files.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w") as f:
            f.write(text)


def run_script(files):
    """The script's exit status and output on a tree of these files."""
    with tempfile.TemporaryDirectory() as root:
        write_tree(root, files)
        done = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)
        return done.returncode, done.stdout


class IncludeCycles(unittest.TestCase):
    def test_two_headers_that_include_each_other_are_a_cycle(self):
        status, out = run_script({
            "lib/CMakeLists.txt": "",
            "lib/src/a.h": '#pragma once\n#include "b.h"\n',
            "lib/src/b.h": '#pragma once\n#include "a.h"\n',
        })
        self.assertEqual(status, 1, out)
        self.assertIn("lib:a -> lib:b -> lib:a", out)
        self.assertIn("lib/src/b.h:2 includes lib/src/a.h", out)

    def test_a_source_and_a_header_of_two_components_can_close_a_cycle(self):
        # x.cpp uses y, and y's header uses x's public header: x and y depend on each other.
        status, out = run_script({
            "lib/CMakeLists.txt": "",
            "lib/include/kdray/x.h": "#pragma once\n",
            "lib/src/x.cpp": '#include <kdray/x.h>\n#include "y.h"\n',
            "lib/src/y.h": "#pragma once\n#include <kdray/x.h>\n",
        })
        self.assertEqual(status, 1, out)
        self.assertIn("lib:x -> lib:y -> lib:x", out)

    def test_a_diamond_and_same_names_in_two_libraries_are_no_cycle(self):
        status, out = run_script({
            "lib/CMakeLists.txt": "",
            "lib/src/top.cpp": '#include "left.h"\n#include "right.h"\n#include <vector>\n',
            "lib/src/left.h": '#pragma once\n#include "base.h"\n',
            "lib/src/right.h": '#pragma once\n#include "base.h"\n',
            # Two components named util, in two libraries: lib/src/other/util.cpp uses lib's base,
            # which uses lib's util. One component per library and name, so no cycle.
            "lib/src/util.h": "#pragma once\n",
            "lib/src/base.h": '#pragma once\n#include "util.h"\n',
            "lib/src/other/CMakeLists.txt": "",
            "lib/src/other/util.cpp": '#include "../base.h"\n',
        })
        self.assertEqual(status, 0, out)
        self.assertIn("no cycle", out)


if __name__ == "__main__":
    unittest.main()
