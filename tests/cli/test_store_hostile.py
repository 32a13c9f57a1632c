#!/usr/bin/python3
"""The centre store against a hostile station (docs/security.md), on a throwaway PostgreSQL
server: a store made fresh and one migrated from schema version 1 with data in it. Each
attack is checked twice: it is refused, and nothing else changed (role memberships, other
stations' rows, the functions' owners and grants, files outside the output folder).

    /usr/bin/python3 tests/cli/test_store_hostile.py --cli palpa-cli --repo REPO

The poison-session test (a valid 100 kB session of 72 million ticks, scored by two workers
under a memory limit) is left out of sanitized runs (ASAN_OPTIONS set): a sanitized scorer
cannot take an address-space limit. The release suite runs it.
"""
import argparse
import hashlib
import os
import resource
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import pg_test_server  # noqa: E402
from constant_session import write_constant_session  # noqa: E402

CLI = REPO = None
SQLITE_HEADER = "53514c69746520666f726d6174203300"
EVIL_IDS = ["/tmp/palpa-abs-evil", "../../../../palpa-evil", "../room-2/" + "ab" * 16, "<script>alert(1)</script>",
            "x" * 300, "", "ab\x1b[2J\x1b[31mFAKE" + "0" * 8, "\u202e" + "a" * 31]


def literal(text):
    return "'" + text.replace("'", "''") + "'"


def meta_of(path):
    db = sqlite3.connect(path)
    meta = dict(db.execute("SELECT key, value FROM meta"))
    version = int(meta.get("format_version", 1))
    if version >= 2:
        count = db.execute("SELECT total(count) FROM sample_blocks").fetchone()[0]
    else:
        count = db.execute("SELECT count(*) FROM samples").fetchone()[0]
    db.close()
    meta["samples"] = int(count)
    return meta


def with_meta(source, path, **values):
    shutil.copyfile(source, path)
    db = sqlite3.connect(path)
    for key, value in values.items():
        db.execute("UPDATE meta SET value = ? WHERE key = ?", (value, key))
    db.commit()
    db.close()
    return path


def files_in(root):
    return sorted(os.path.join(d, n) for d, _, names in os.walk(root) for n in names)


class StoreFixture(unittest.TestCase):
    """One store (a database) on the module's server, with station, worker and coordinator
    logins and one session pushed; subclasses say how the store is made (prepare_store)."""
    DB = None
    pg = None
    dir = None
    logins = False

    @classmethod
    def setUpClass(cls):
        if cls.DB is None:
            raise unittest.SkipTest("base class")
        if StoreFixture.pg is None:
            StoreFixture.pg = pg_test_server.server_for_tests()
            StoreFixture.dir = tempfile.mkdtemp(prefix="palpa-hostile-")
            upgrade = run_cli("session", "upgrade", os.path.join(REPO, "data", "sessions", "sloppy.palpa"), "--out",
                              StoreFixture.dir)
            assert upgrade.returncode == 0, upgrade.stderr
        cls.small = os.path.join(StoreFixture.dir, "sloppy.palpa")  # format 2, about 100 kB
        cls.pg.sql("CREATE DATABASE %s" % cls.DB)
        cls.prepare_store()
        if not StoreFixture.logins:  # the group roles exist once a store was made
            for user, group in (("station_1", "palpa_station"), ("station_2", "palpa_station"),
                                ("station_evil", "palpa_station"), ("worker", "palpa_worker"),
                                ("coord", "palpa_coordinator")):
                StoreFixture.pg.add_login(user, group)
            StoreFixture.logins = True
        pushed = cls.push("station_1", "room-1", with_meta(cls.small, cls.path("room1.palpa"), id=cls.new_id(1)))
        assert pushed.returncode == 0, pushed.stderr

    @classmethod
    def path(cls, name):
        return os.path.join(cls.dir, cls.DB + "-" + name)

    @classmethod
    def new_id(cls, n):
        return hashlib.sha256(("%s-%d" % (cls.DB, n)).encode()).hexdigest()[:32]

    @classmethod
    def push(cls, user, station, *files, outbox=None):
        return run_cli("store", "push", *files, "--store", cls.pg.url(cls.DB, user), "--station", station,
                       "--outbox", outbox or cls.path("outbox-" + user))

    def sql(self, text, user=None, check=True):
        return self.pg.psql_stdin(text, self.DB, user, check=check)

    def state(self):
        """Everything an attack must leave as it was."""
        queries = [
            "SELECT r.rolname || '>' || m.rolname FROM pg_auth_members a JOIN pg_roles r ON r.oid = a.roleid "
            "JOIN pg_roles m ON m.oid = a.member ORDER BY 1",
            "SELECT name || ':' || db_user FROM stations ORDER BY 1",
            "SELECT id || ':' || session_id || ':' || station || ':' || sha256 || ':' || uploaded_by || ':' || "
            "trainee_id || ':' || case_id FROM sessions ORDER BY id",
            "SELECT id || ':' || sha256 FROM cases ORDER BY id",
            "SELECT count(*) FROM scores",
            "SELECT proname || ':' || proowner::regrole || ':' || coalesce(proacl::text, '') FROM pg_proc "
            "WHERE proname LIKE 'palpa%' ORDER BY 1",
            "SELECT c.relname || ':' || c.relowner::regrole FROM pg_class c JOIN pg_namespace n ON n.oid = c.relnamespace "
            "WHERE n.nspname = 'public' ORDER BY 1",
        ]
        return [self.pg.sql(q, self.DB) for q in queries]

    def call_push(self, user="station_evil", check=False, **override):
        """palpa_push_session called directly, as a station could with psql."""
        args = {"station": literal("room-evil"), "id": literal(self.new_id(900)), "trainee": literal("mallory"),
                "title": literal(""), "case": "'{}'::jsonb", "started": "now()", "mode": literal("trainee"),
                "complete": "true", "samples": "1", "file_name": literal("x.palpa"), "events": "'[]'::jsonb",
                "file": "'\\x%s'::bytea" % SQLITE_HEADER}
        args.update(override)
        order = ("station", "id", "trainee", "title", "case", "started", "mode", "complete", "samples", "file_name",
                 "events", "file")
        text = "SELECT * FROM public.palpa_push_session(%s);" % ", ".join(args[k] for k in order)
        return self.sql(text, user, check)



class HostileStation(StoreFixture):
    """Attacks on one store; subclasses say which (fresh, or migrated from version 1)."""

    # -- the server functions -------------------------------------------------------------
    def test_temporary_tables_are_refused(self):
        before = self.state()
        res = self.sql("CREATE TEMP TABLE stations (name text, db_user text);", "station_evil", check=False)
        self.assertNotEqual(res.returncode, 0)
        self.assertIn("permission denied to create temporary tables", res.stderr)
        for text in ("CREATE TABLE public.stations2 (x int);", "CREATE SCHEMA evil;",
                     "CREATE FUNCTION public.f() RETURNS int LANGUAGE sql AS 'SELECT 1';"):
            self.assertNotEqual(self.sql(text, "station_evil", check=False).returncode, 0, text)
        self.assertEqual(self.state(), before)

    def test_shadow_tables_and_triggers_do_not_run_as_the_owner(self):
        # Even with TEMP granted by mistake, the function names public.stations: the shadow
        # table and its trigger are never touched, so no grant and no impersonation.
        self.pg.sql("GRANT TEMPORARY ON DATABASE %s TO station_evil" % self.DB)
        try:
            before = self.state()
            attack = """
CREATE TEMP TABLE stations (name text PRIMARY KEY, db_user text, first_seen timestamptz DEFAULT now());
INSERT INTO pg_temp.stations VALUES ('room-1', 'station_evil');
CREATE TEMP TABLE sessions (id bigint, session_id text, sha256 text, uploaded_by text);
CREATE FUNCTION pg_temp.escalate() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  EXECUTE 'GRANT palpa_coordinator TO station_evil';
  RAISE EXCEPTION 'leak: %%', (SELECT string_agg(name, ',') FROM public.trainees);
END $$;
CREATE TRIGGER escalate BEFORE INSERT OR UPDATE ON pg_temp.stations FOR EACH ROW EXECUTE FUNCTION pg_temp.escalate();
CREATE TRIGGER escalate BEFORE INSERT OR UPDATE ON pg_temp.sessions FOR EACH ROW EXECUTE FUNCTION pg_temp.escalate();
SELECT * FROM public.palpa_push_session('room-1', '%s', 'mallory', '', '{}'::jsonb, now(), 'trainee', true, 1,
                                        'x.palpa', '[]'::jsonb, '\\x%s'::bytea);
""" % (self.new_id(901), SQLITE_HEADER)
            res = self.sql(attack, "station_evil", check=False)
            self.assertNotEqual(res.returncode, 0)
            self.assertIn('station "room-1" is registered to another login', res.stderr)
            self.assertNotIn("leak", res.stderr)
            self.assertNotIn("station_1", res.stderr)
            self.assertEqual(self.state(), before)
        finally:
            self.pg.sql("REVOKE TEMPORARY ON DATABASE %s FROM station_evil" % self.DB)
        self.assertEqual(self.pg.sql("SELECT pg_has_role('station_evil', 'palpa_coordinator', 'MEMBER')"), "f")

    def test_the_view_leaks_nothing_through_a_stations_own_conditions(self):
        # Without a security barrier, a cheap condition that raises an error naming its
        # argument ran before the view's filter and printed other stations' ids and trainees.
        theirs = self.pg.sql("SELECT string_agg(session_id, ' ') FROM sessions WHERE uploaded_by <> 'station_evil'",
                             self.DB).split()
        trainees = self.pg.sql("SELECT string_agg(DISTINCT t.name, ' ') FROM trainees t JOIN sessions s ON "
                               "s.trainee_id = t.id WHERE s.uploaded_by <> 'station_evil' AND t.id NOT IN (SELECT "
                               "trainee_id FROM sessions WHERE uploaded_by = 'station_evil')", self.DB).split()
        self.assertTrue(theirs)
        for attack in ("SELECT * FROM station_sessions WHERE has_database_privilege(session_id, 'CONNECT');",
                       "SELECT * FROM station_sessions WHERE has_database_privilege('%s', sha256);" % self.DB,
                       "SET enable_nestloop = off; SELECT * FROM station_sessions WHERE CASE WHEN trainee "
                       "NOT IN ('x') THEN trainee::int ELSE 0 END = 1;"):
            res = self.sql(attack, "station_evil", check=False)
            for leaked in theirs + [t for t in trainees if len(t) > 3]:
                self.assertNotIn(leaked, res.stderr + res.stdout, attack)

    def test_large_objects_are_refused(self):
        res = self.sql("SELECT lo_from_bytea(0, '\\x00'::bytea);", "station_evil", check=False)
        self.assertNotEqual(res.returncode, 0)
        self.assertIn("permission denied", res.stderr)

    def test_the_functions_are_owned_and_granted_safely(self):
        def function(column):
            return self.pg.sql("SELECT %s FROM pg_proc WHERE proname = 'palpa_push_session'" % column, self.DB)

        self.assertEqual(function("proowner::regrole"), "palpa_owner")
        self.assertEqual(function("prosecdef"), "t")
        self.assertEqual(function("array_to_string(proconfig, ';')"),
                         "search_path=pg_catalog, public, pg_temp;lock_timeout=5s")
        acl = function("proacl::text")
        self.assertEqual(sorted(a.split("=")[0] for a in acl.strip("{}").split(",")), ["palpa_owner", "palpa_station"])
        for helper in ("palpa_check_text", "palpa_check_session", "palpa_check_name", "palpa_check_document",
                       "palpa_check_quota"):
            self.assertEqual(self.pg.sql("SELECT proowner::regrole || ' ' || proacl::text FROM pg_proc "
                                         "WHERE proname = '%s'" % helper, self.DB), "palpa_owner {palpa_owner=X/palpa_owner}")
        self.assertEqual(self.pg.sql("SELECT rolcanlogin || ' ' || rolcreaterole || ' ' || rolsuper FROM pg_roles "
                                     "WHERE rolname = 'palpa_owner'"), "false false false")
        for role in ("palpa_station", "palpa_worker", "palpa_coordinator"):
            self.assertEqual(self.pg.sql("SELECT has_database_privilege('%s', '%s', 'TEMP') || ' ' || "
                                         "has_database_privilege('%s', '%s', 'CREATE') || ' ' || "
                                         "has_schema_privilege('%s', 'public', 'CREATE')"
                                         % (role, self.DB, role, self.DB, role), self.DB), "false false false", role)

    def test_bad_values_are_refused_by_the_server(self):
        before = self.state()
        cases = [
            ({"id": literal(i)}, "field id") for i in EVIL_IDS + ["A" * 200000, "AB" * 16]
        ] + [
            ({"trainee": literal("ali\x01ce")}, "field trainee"),
            ({"trainee": literal("\u202eecila")}, "field trainee"),
            ({"trainee": literal("t" * 200000)}, "field trainee"),
            ({"trainee": literal("")}, "field trainee"),
            ({"station": literal("room\x1b[2J")}, "field station"),
            ({"station": literal("s" * 100)}, "field station"),
            ({"mode": literal("root")}, "field mode"),
            ({"started": "'infinity'::timestamptz"}, "field started_at"),
            ({"started": "'1900-01-01'::timestamptz"}, "field started_at"),
            ({"started": "now() + interval '10 years'"}, "field started_at"),
            ({"samples": "(-9223372036854775807 - 1)"}, "field samples"),
            ({"samples": "72000001"}, "field samples"),
            ({"file_name": literal("f" * 100000)}, "field file name"),
            ({"file_name": literal("../evil.palpa")}, "field file name"),
            ({"file": "'\\x00000000'::bytea"}, "field file"),
            ({"complete": "false"}, "field complete"),
            ({"case": "'[1, 2]'::jsonb"}, "field case"),
            ({"events": "'{}'::jsonb"}, "field events"),
            ({"title": literal("t\x07")}, "field case title"),
            ({"trainee": literal("al\u200bice")}, "field trainee"),
            ({"trainee": literal("\ufeffbob")}, "field trainee"),
            ({"trainee": literal("bob\u061c")}, "field trainee"),
            ({"station": literal("r\u03bfom-1")}, "field station"),
            ({"station": literal("../room")}, "field station"),
            # 1e131071 is a few bytes of jsonb and 131072 characters of text: refused at once.
            ({"case": "('{\"a\": [' || repeat('1e131071,', 999) || '1]}')::jsonb"}, "field case"),
            ({"events": "('[' || repeat('1e-16000,', 999) || '1]')::jsonb"}, "field events"),
        ]
        for override, field in cases:
            with self.subTest(field=field, value=str(override)[:60]):
                res = self.call_push(**override)
                self.assertNotEqual(res.returncode, 0)
                self.assertIn(field, res.stderr)
                value = list(override.values())[0].strip("'")
                if len(value) >= 8:
                    self.assertNotIn(value[:8], res.stderr)  # the value is not echoed
        self.assertEqual(self.state(), before)

    def test_the_file_size_limit_is_the_stores(self):
        self.pg.sql("UPDATE store_settings SET max_file_bytes = 4096", self.DB)
        try:
            before = self.state()
            res = self.call_push(file="'\\x%s'::bytea || decode(repeat('00', 5000), 'hex')" % SQLITE_HEADER)
            self.assertNotEqual(res.returncode, 0)
            self.assertIn("field file: larger than the store accepts (4096 bytes", res.stderr)
            self.assertEqual(self.state(), before)
            # A station may not change the limit.
            self.assertNotEqual(self.sql("UPDATE store_settings SET max_file_bytes = 1073741824", "station_evil",
                                         check=False).returncode, 0)
        finally:
            self.pg.sql("UPDATE store_settings SET max_file_bytes = 67108864", self.DB)

    def test_the_case_key_is_the_servers(self):
        # Two sessions with one case document make one case row, keyed by the server's hash.
        for n in (2, 3):
            res = self.push("station_2", "room-2", with_meta(self.small, self.path("case%d.palpa" % n),
                                                             id=self.new_id(n)))
            self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM cases WHERE sha256 <> encode(sha256(convert_to("
                                     "document::text, 'UTF8')), 'hex')", self.DB), "0")
        self.assertEqual(self.pg.sql("SELECT count(DISTINCT case_id) FROM sessions WHERE session_id IN ('%s', '%s')"
                                     % (self.new_id(2), self.new_id(3)), self.DB), "1")

    # -- through palpa-cli store push --------------------------------------------------------
    def test_pushing_as_another_station_is_refused(self):
        before = self.state()
        res = self.push("station_evil", "room-1", with_meta(self.small, self.path("imp.palpa"), id=self.new_id(10)))
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn('station "room-1" is registered to another login', res.stderr)
        self.assertNotIn("station_1", res.stderr + res.stdout)
        self.assertEqual(self.state(), before)

    def test_another_stations_session_id_is_refused_without_its_checksum(self):
        # room-1's session pushed again by another login, under its own station.
        copy = with_meta(self.small, self.path("taken.palpa"), id=self.new_id(1), trainee="mallory")
        before = self.state()
        stored_sha = self.pg.sql("SELECT sha256 FROM sessions WHERE session_id = '%s'" % self.new_id(1), self.DB)
        res = self.push("station_evil", "room-evil", copy)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("this id is taken", res.stderr)
        self.assertNotIn(stored_sha, res.stderr + res.stdout)
        self.assertNotIn("room-1", res.stderr + res.stdout)
        after = self.state()
        self.assertEqual(after[2:], before[2:])  # its station may now exist; nothing else changed

    def test_unsafe_ids_are_refused_before_anything_is_queued(self):
        outbox = self.path("outbox-unsafe")
        before = self.state()
        for n, bad in enumerate(EVIL_IDS):
            with self.subTest(id=bad[:40]):
                f = with_meta(self.small, self.path("unsafe%d.palpa" % n), id=bad)
                res = self.push("station_evil", "room-evil", f, outbox=outbox)
                self.assertEqual(res.returncode, 2, res.stderr)
                self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
                self.assertIn("field id: not a session id", res.stderr)
                self.assertNotIn("\x1b", res.stderr + res.stdout)
                self.assertNotIn("\u202e", res.stderr + res.stdout)
                self.assertEqual(files_in(outbox), [])
        # Not while the server is away either: nothing is queued.
        f = with_meta(self.small, self.path("unsafe-offline.palpa"), id="../../x")
        res = run_cli("store", "push", f, "--store", "host=127.0.0.1 port=%d dbname=x user=y connect_timeout=3"
                      % pg_test_server.free_port(), "--station", "room-evil", "--outbox", outbox)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertEqual(files_in(outbox), [])
        self.assertEqual(self.state(), before)

    def test_control_characters_and_nul_in_names_are_refused(self):
        before = self.state()
        for n, trainee in enumerate(("ali\x00ce", "ali\x1b[2Jce", "ali\u202ece", "t" * 129)):
            with self.subTest(trainee=trainee[:20]):
                f = with_meta(self.small, self.path("name%d.palpa" % n), id=self.new_id(20 + n), trainee=trainee)
                res = self.push("station_evil", "room-evil", f)
                self.assertEqual(res.returncode, 2, res.stderr)
                self.assertIn("field trainee", res.stderr)
                self.assertNotIn("\x1b", res.stderr + res.stdout)
        res = self.push("station_evil", "room\x1b[2J", with_meta(self.small, self.path("st.palpa"), id=self.new_id(30)))
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("station name", res.stderr)
        self.assertNotIn("\x1b", res.stderr + res.stdout)
        self.assertEqual(self.state(), before)

    def test_forged_metadata_is_not_scored(self):
        # The row says one trainee, the file another: the worker ends it with the reason.
        forged = with_meta(self.small, self.path("forged.palpa"), id=self.new_id(40))
        meta = meta_of(forged)
        with open(forged, "rb") as f:
            data = f.read().hex()
        res = self.call_push(id=literal(meta["id"]), trainee=literal("someone-else"), started=literal(meta["started_at"]),
                             mode=literal("scripted"), samples=str(meta["samples"]), case="%s::jsonb" % literal(meta["case"]),
                             file="'\\x%s'::bytea" % data)
        self.assertEqual(res.returncode, 0, res.stderr)
        work = run_cli("batch", "--store", self.pg.url(self.DB, "worker"), "--worker", "--jobs", "1", timeout=600)
        self.assertEqual(work.returncode, 2, work.stderr)
        row = self.pg.sql("SELECT w.done || ' ' || coalesce(w.last_error, '') FROM work_queue w JOIN sessions s "
                          "ON s.id = w.session_id WHERE s.session_id = '%s'" % meta["id"], self.DB)
        self.assertTrue(row.startswith("true "), row)
        self.assertIn("the file's trainee differs from what the station sent with it", row)
        self.assertIn("session %s from station room-evil" % meta["id"], row)
        self.assertNotIn("/proc/self/fd", work.stderr + row)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM scores sc JOIN sessions s ON s.id = sc.session_id "
                                     "WHERE s.session_id = '%s'" % meta["id"], self.DB), "0")

    # -- reports -------------------------------------------------------------------------------
    def test_reports_write_only_inside_their_folder(self):
        root = tempfile.mkdtemp(prefix="report-", dir=self.dir)
        out = os.path.join(root, "out")
        outside_before = [p for p in files_in(self.dir) if not p.startswith(out)]
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out, timeout=600)
        self.assertIn(res.returncode, (0, 2), res.stderr)
        self.assertTrue(os.path.exists(os.path.join(out, "summary.csv")), res.stderr)
        self.assertTrue(os.path.exists(os.path.join(out, "cohort.html")), res.stderr)
        self.assertEqual([p for p in files_in(self.dir) if not p.startswith(out)], outside_before)
        for name in files_in(os.path.join(out, "stored")):
            rel = os.path.relpath(name, os.path.join(out, "stored"))
            self.assertRegex(rel, r"^[a-z0-9-]+-[0-9a-f]{8}/[0-9]+\.palpa$")
        self.assertNotIn("\x1b", res.stderr + res.stdout)


class FreshStore(HostileStation):
    DB = "fresh"

    @classmethod
    def prepare_store(cls):
        res = run_cli("store", "init", cls.pg.url(cls.DB))
        assert res.returncode == 0, res.stderr

    def test_poison_session_is_retired_and_workers_stay_up(self):
        if os.environ.get("ASAN_OPTIONS"):
            self.skipTest("a sanitized scorer takes no address-space limit; the release suite runs this")
        ticks = int(os.environ.get("PALPA_POISON_TICKS", "72000000"))
        constant = self.path("constant.palpa")
        write_constant_session(constant, REPO, ticks)
        poison = with_meta(constant, self.path("poison.palpa"), id=self.new_id(50))
        self.assertLess(os.path.getsize(poison), 200000)
        normal = [with_meta(self.small, self.path("normal%d.palpa" % n), id=self.new_id(60 + n)) for n in range(2)]
        res = self.push("station_1", "room-1", poison, *normal)
        self.assertEqual(res.returncode, 0, res.stderr)

        def limited():
            resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))

        args = [CLI, "batch", "--store", self.pg.url(self.DB, "worker"), "--worker", "--jobs", "1",
                "--score-memory", "1024", "--score-seconds", "20"]
        workers = [subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                    env=self.pg.env(), preexec_fn=limited) for _ in range(2)]
        outputs = [w.communicate(timeout=900) for w in workers]
        for w, (out, err) in zip(workers, outputs):
            self.assertGreaterEqual(w.returncode, 0, err)  # never killed by a signal
            self.assertIn(w.returncode, (0, 2), err)
        row = self.pg.sql("SELECT w.done || ' ' || w.attempts || ' ' || coalesce(w.last_error, '') || ' ' || "
                          "(SELECT count(*) FROM scores sc WHERE sc.session_id = w.session_id) FROM work_queue w "
                          "JOIN sessions s ON s.id = w.session_id WHERE s.session_id = '%s'" % self.new_id(50), self.DB)
        self.assertTrue(row.startswith("true "), row)
        scored = row.endswith(" 1")
        self.assertTrue(scored or "retired after 3 attempts" in row, row)
        for n in range(2):
            self.assertEqual(self.pg.sql("SELECT count(*) FROM scores sc JOIN sessions s ON s.id = sc.session_id "
                                         "WHERE s.session_id = '%s'" % self.new_id(60 + n), self.DB), "1")
        self.assertEqual([n for n in os.listdir(tempfile.gettempdir()) if n.startswith("palpa-worker-")], [])

    def test_a_following_worker_reconnects_after_a_server_restart(self):
        worker = subprocess.Popen([CLI, "batch", "--store", self.pg.url(self.DB, "worker"), "--worker", "--follow",
                                   "--jobs", "1"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                  env=self.pg.env())
        try:
            time.sleep(2)
            self.pg.stop()
            time.sleep(3)
            self.pg.start()
            late = with_meta(self.small, self.path("late.palpa"), id=self.new_id(70))
            self.assertEqual(self.push("station_1", "room-1", late).returncode, 0)
            # Everything gets scored, the session the worker held when the server went away too.
            deadline = time.time() + 300
            while time.time() < deadline:
                if self.pg.sql("SELECT count(*) FROM work_queue WHERE NOT done", self.DB) == "0":
                    break
                time.sleep(1)
            self.assertIsNone(worker.poll(), "the worker ended")
        finally:
            worker.terminate()
            out, err = worker.communicate(timeout=60)
        self.assertIn("trying again in", err)
        self.assertEqual(self.pg.sql("SELECT count(*) FROM scores sc JOIN sessions s ON s.id = sc.session_id "
                                     "WHERE s.session_id = '%s'" % self.new_id(70), self.DB), "1", err)

    def test_a_database_not_in_utf8_is_refused(self):
        self.pg.sql("CREATE DATABASE ascii ENCODING 'SQL_ASCII' LC_COLLATE 'C' LC_CTYPE 'C' TEMPLATE template0")
        res = run_cli("store", "init", self.pg.url("ascii"))
        self.assertEqual(res.returncode, 1, res.stdout)
        self.assertIn("is encoded in SQL_ASCII; the store needs UTF8", res.stderr)
        self.assertEqual(self.pg.sql("SELECT to_regclass('palpa_schema') IS NULL", "ascii"), "t")

    def test_the_outbox_never_writes_through_a_link_nor_replaces_a_queued_file(self):
        outbox = self.path("outbox-links")
        os.makedirs(outbox)
        victim = self.path("victim.txt")
        with open(victim, "w") as f:
            f.write("precious")
        sid = self.new_id(90)
        down = "host=127.0.0.1 port=%d dbname=x user=y connect_timeout=3" % pg_test_server.free_port()
        for n in range(2):  # links where its copy and its record would go
            os.symlink(victim, os.path.join(outbox, sid + (".palpa" if n == 0 else ".json")))
        f = with_meta(self.small, self.path("linked.palpa"), id=sid)
        res = run_cli("store", "push", f, "--store", down, "--station", "room-1", "--outbox", outbox)
        self.assertEqual(res.returncode, 2, res.stderr)
        self.assertIn("already holds another session with this id", res.stderr)
        with open(victim) as v:
            self.assertEqual(v.read(), "precious")
        # Another file with an id already queued is refused, the queued one kept.
        clean = self.path("outbox-clean")
        first = with_meta(self.small, self.path("first.palpa"), id=self.new_id(91))
        self.assertEqual(run_cli("store", "push", first, "--store", down, "--station", "room-1", "--outbox",
                                 clean).returncode, 0)
        second = with_meta(self.small, self.path("second.palpa"), id=self.new_id(91), trainee="other")
        res = run_cli("store", "push", second, "--store", down, "--station", "room-1", "--outbox", clean)
        self.assertEqual(res.returncode, 2, res.stderr)
        with open(os.path.join(clean, self.new_id(91) + ".palpa"), "rb") as q, open(first, "rb") as o:
            self.assertEqual(q.read(), o.read())

    def test_settings_mistakes_are_not_queued_and_a_newer_store_queues(self):
        outbox = self.path("outbox-settings")
        f = with_meta(self.small, self.path("settings.palpa"), id=self.new_id(80))
        for conninfo in ("host=127.0.0.1 port=26848x dbname=x", "host=127.0.0.1 dbname=x sslmode=requir",
                         "service=nosuch-palpa-service"):
            with self.subTest(conninfo=conninfo):
                res = run_cli("store", "push", f, "--store", conninfo, "--station", "room-1", "--outbox", outbox,
                              PGSERVICEFILE=os.devnull)
                self.assertEqual(res.returncode, 1, res.stderr + res.stdout)
                self.assertEqual(len(res.stderr.strip().splitlines()), 1, res.stderr)
                self.assertEqual(files_in(outbox), [])
        self.pg.sql("CREATE DATABASE newer")
        self.assertEqual(run_cli("store", "init", self.pg.url("newer")).returncode, 0)
        self.pg.sql("INSERT INTO palpa_schema(version) VALUES (99)", "newer")
        res = run_cli("store", "push", f, "--store", self.pg.url("newer", "station_1"), "--station", "room-1",
                      "--outbox", outbox)
        self.assertEqual(res.returncode, 3, res.stderr)
        self.assertIn("newer than this Palpa knows", res.stderr)
        self.assertIn("wait in the outbox", res.stderr)
        self.assertEqual([os.path.basename(p) for p in files_in(outbox)],
                         [self.new_id(80) + ".json", self.new_id(80) + ".palpa"])


class MigratedStore(HostileStation):
    """A store made by schema version 1, holding what version 1 let stations store (ids that
    are paths or markup, a case under a key its document does not hash to), then migrated."""
    DB = "migrated"

    @classmethod
    def prepare_store(cls):
        res = run_cli("store", "init", cls.pg.url(cls.DB), "--schema-version", "1")
        assert res.returncode == 0, res.stderr
        with open(os.path.join(REPO, "data", "sessions", "sloppy.palpa"), "rb") as f:
            data = f.read().hex()
        rows = ["INSERT INTO stations(name, db_user) VALUES ('room-2', 'station_2'), "
                "('zz<script>\x1b[31m', 'station_2');",
                "INSERT INTO trainees(name) VALUES ('alice'), ('bob');",
                "INSERT INTO cases(sha256, title, document) VALUES ('%s', 'fake', '{\"title\": \"fake\"}');" % ("f" * 64),
                "INSERT INTO cases(sha256, title, document) VALUES ('%s', 'same', '{\"title\": \"fake\"}');" % ("e" * 64)]
        for n, sid in enumerate(["ab" * 16] + EVIL_IDS[:5]):
            station = "room-2" if n % 2 == 0 else "zz<script>\x1b[31m"
            rows.append("INSERT INTO sessions(session_id, station, trainee_id, case_id, started_at, mode, complete, "
                        "samples, size_bytes, sha256, file_name, events, file, uploaded_by) VALUES "
                        "(%s, %s, 1 + %d %% 2, 1 + %d %% 2, now(), 'scripted', true, 1, %d, '%s', 'f.palpa', '[]', "
                        "'\\x%s'::bytea, 'station_2');" % (literal(sid), literal(station), n, n, len(data) // 2,
                                                           hashlib.sha256(bytes.fromhex(data)).hexdigest(), data))
        res = cls.pg.psql_stdin("\n".join(rows), cls.DB)
        assert res.returncode == 0, res.stderr
        res = run_cli("store", "init", cls.pg.url(cls.DB))
        assert res.returncode == 0 and "schema version 3 (was 1)" in res.stdout, res.stdout + res.stderr

    def test_the_migration_rekeys_cases_and_keeps_the_data(self):
        ids = ", ".join(literal(i) for i in ["ab" * 16] + EVIL_IDS[:5])
        self.assertEqual(self.pg.sql("SELECT count(*) FROM sessions WHERE session_id IN (%s)" % ids, self.DB), "6")
        self.assertEqual(self.pg.sql("SELECT count(*) FROM cases WHERE document::text = '{\"title\": \"fake\"}'",
                                     self.DB), "1")
        self.assertEqual(self.pg.sql("SELECT count(*) FROM cases WHERE sha256 <> encode(sha256(convert_to("
                                     "document::text, 'UTF8')), 'hex')", self.DB), "0")


def run_cli(*args, timeout=300, **env):
    pg = StoreFixture.pg
    environment = pg.env(**env) if pg else dict(os.environ, **env)
    return subprocess.run([CLI, *args], capture_output=True, text=True, env=environment, timeout=timeout)


def tearDownModule():
    if StoreFixture.pg:
        StoreFixture.pg.close()
        shutil.rmtree(StoreFixture.dir, ignore_errors=True)


def main():
    global CLI, REPO
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    args, rest = ap.parse_known_args()
    CLI, REPO = os.path.abspath(args.cli), os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
