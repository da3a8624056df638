#!/usr/bin/env python3
"""biovision_ros_common.atomic_file: whole files with the umask's mode, nothing left behind on failure."""

import os
import stat
import sys
import tempfile
import unittest

import rostest
from biovision_ros_common.atomic_file import write_atomically


class WriteAtomically(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="atomic_file_test")

    def test_text_and_bytes_replace_the_file_whole_with_the_umasks_mode(self):
        path = os.path.join(self.folder, "report.md")
        write_atomically(path, "first\n")
        write_atomically(path, "second ü\n")
        with open(path, encoding="utf-8") as f:
            self.assertEqual(f.read(), "second ü\n")
        write_atomically(path, b"\x00\xff")
        with open(path, "rb") as f:
            self.assertEqual(f.read(), b"\x00\xff")
        mask = os.umask(0o022)
        os.umask(mask)
        self.assertEqual(stat.S_IMODE(os.stat(path).st_mode), 0o666 & ~mask)  # mkstemp alone gives 0600
        self.assertEqual(os.listdir(self.folder), ["report.md"])

    def test_a_missing_folder_raises_and_a_failed_write_leaves_no_temporary(self):
        with self.assertRaises(OSError):
            write_atomically(os.path.join(self.folder, "missing", "x.json"), "{}")
        path = os.path.join(self.folder, "kept.json")
        write_atomically(path, "{}")
        with self.assertRaises(TypeError):
            write_atomically(path, 42)  # neither str nor bytes: raises inside the write
        with open(path) as f:
            self.assertEqual(f.read(), "{}")  # the old file stays
        self.assertEqual(os.listdir(self.folder), ["kept.json"])


if __name__ == "__main__":
    rostest.rosrun("biovision_ros_common", "atomic_file", WriteAtomically, sys.argv)
