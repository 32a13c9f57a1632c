#!/usr/bin/python3
"""tools/check_function_length.py: no function in the product's sources is longer than 80
lines unless a "Long:" comment above it says why; the scanner finds functions through
comments, strings, lambdas, constructor initializer lists and nested classes.

    /usr/bin/python3 tests/tools/test_check_function_length.py --repo REPO
"""

import argparse
import importlib.util
import os
import sys
import tempfile
import unittest

REPO = None


def load_checker():
    spec = importlib.util.spec_from_file_location("check_function_length",
                                                  os.path.join(REPO, "tools", "check_function_length.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def body(lines):
    return "\n".join(f"  x += {k};" for k in range(lines))


class FunctionLength(unittest.TestCase):
    def test_the_repository_has_no_long_function(self):
        checker = load_checker()
        found = []
        for folder in checker.DEFAULT_FOLDERS:
            for root, _, names in os.walk(os.path.join(REPO, folder)):
                for name in sorted(names):
                    if name.endswith(checker.SOURCES):
                        path = os.path.join(root, name)
                        found += [f"{os.path.relpath(path, REPO)}:{line}: {fn} ({n} lines)"
                                  for fn, line, n in checker.long_functions(path, 80)]
        self.assertEqual(found, [], "\n".join(found))

    def test_functions_are_found_with_their_lines(self):
        checker = load_checker()
        text = "\n".join([
            "namespace a {",                                   # 1
            "// a comment with a { brace",                     # 2
            "int f(int x) {",                                  # 3
            '  const char* s = "}{";',                         # 4
            "  auto g = [&](int y) { return y + 1; };",        # 5
            "  return g(x);",                                  # 6
            "}",                                               # 7
            "struct S {",                                      # 8
            "  S() : v_{1}, w_(2) {",                          # 9
            "    v_ += w_;",                                   # 10
            "  }",                                             # 11
            "  int v_, w_;",                                   # 12
            "};",                                              # 13
            "const int table[] = {1, 2, 3};",                  # 14
            "double S::h() const noexcept {",                  # 15
            "  return 0.0;",                                   # 16
            "}",                                               # 17
            "}  // namespace a",                               # 18
        ])
        self.assertEqual(list(checker.functions(text)), [("f", 3, 7), ("S", 9, 11), ("S::h", 15, 17)])

    def test_a_long_function_is_reported_unless_its_comment_says_why(self):
        checker = load_checker()
        with tempfile.TemporaryDirectory() as root:
            path = os.path.join(root, "long.cpp")
            with open(path, "w") as f:
                f.write("int long_one() {\n" + body(85) + "\n}\n\n"
                        "// Long: one table of 90 cases; split, it would be read in pieces.\n"
                        "int waived() {\n" + body(90) + "\n}\n\n"
                        "int short_one() {\n" + body(78) + "\n}\n")
            self.assertEqual(list(checker.long_functions(path, 80)), [("long_one", 1, 87)])


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True)
    args, rest = parser.parse_known_args()
    REPO = os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest)
