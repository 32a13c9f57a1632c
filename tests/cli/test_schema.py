#!/usr/bin/env python3
"""Checks data/schema/palpa-case.schema.json against the bundled and invalid cases.

Usage: python3 tests/cli/test_schema.py --repo REPO_ROOT [unittest options]
Needs only the standard library and jsonschema.
"""

import argparse
import glob
import json
import os
import sys
import unittest

import jsonschema

REPO = None  # set in main()


def load_json(path):
    """Parses strict JSON; returns None when Python cannot read it as JSON
    (not JSON, bare NaN/Infinity, or nesting too deep for the parser)."""
    def reject(name):
        raise ValueError(f"non-standard constant {name}")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f, parse_constant=reject)
    except (ValueError, RecursionError):
        return None


class SchemaTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with open(os.path.join(REPO, "data", "schema", "palpa-case.schema.json"), encoding="utf-8") as f:
            cls.schema = json.load(f)
        cls.validator = jsonschema.Draft202012Validator(cls.schema)
        cls.invalid_dir = os.path.join(REPO, "tests", "data", "invalid")
        with open(os.path.join(cls.invalid_dir, "expected.json"), encoding="utf-8") as f:
            cls.expected = json.load(f)

    def test_schema_is_valid(self):
        jsonschema.Draft202012Validator.check_schema(self.schema)
        self.assertEqual(self.schema["$schema"], "https://json-schema.org/draft/2020-12/schema")

    def test_bundled_cases_conform(self):
        cases = sorted(glob.glob(os.path.join(REPO, "data", "cases", "*.json")))
        self.assertTrue(cases, "no bundled cases found")
        for path in cases:
            with self.subTest(case=os.path.basename(path)):
                doc = load_json(path)
                self.assertIsNotNone(doc, "not strict JSON")
                errors = [f"{e.json_path}: {e.message}" for e in self.validator.iter_errors(doc)]
                self.assertEqual(errors, [])

    def test_expected_covers_invalid_files(self):
        files = {os.path.basename(p) for p in glob.glob(os.path.join(self.invalid_dir, "*.json"))}
        files.discard("expected.json")
        self.assertEqual(files, set(self.expected))

    def test_schema_catchable_errors_are_rejected(self):
        for name, exp in sorted(self.expected.items()):
            if not exp["schema"]:
                continue
            with self.subTest(file=name):
                doc = load_json(os.path.join(self.invalid_dir, name))
                self.assertIsNotNone(doc, "marked schema: true but not parseable as JSON")
                self.assertFalse(self.validator.is_valid(doc), "schema accepts it")

    def test_other_errors_are_beyond_the_schema(self):
        # Keeps the "schema" marks honest: what the schema cannot express must pass it.
        for name, exp in sorted(self.expected.items()):
            if exp["schema"]:
                continue
            doc = load_json(os.path.join(self.invalid_dir, name))
            if doc is None:
                continue  # a reading error: no document to check
            with self.subTest(file=name):
                errors = [f"{e.json_path}: {e.message}" for e in self.validator.iter_errors(doc)]
                self.assertEqual(errors, [], "the schema rejects it: mark it schema: true")


def main():
    global REPO
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repo", required=True, help="repository root")
    args, rest = ap.parse_known_args()
    REPO = os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest)


if __name__ == "__main__":
    main()
