#!/usr/bin/python3
"""The centre store against a hostile station, second round (docs/security.md, "The store's
second round"): the work a station can cause, the queue's fairness, amplification, forged
trainees, look-alike names, locks a station holds, and the setup of docs/centre.md with an
administrator who is not a superuser. Each attack is refused (or flagged) and nothing else
changes. Every store is a database of its own on one throwaway PostgreSQL server.

    /usr/bin/python3 tests/cli/test_store_hostile_queue.py --cli palpa-cli --repo REPO
"""
import argparse
import csv
import hashlib
import json
import os
import re
import resource
import subprocess
import sys
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import test_store_hostile as hostile  # noqa: E402
from constant_session import write_constant_session  # noqa: E402
from test_store_hostile import StoreFixture, literal, run_cli, with_meta  # noqa: E402

SANITIZED = bool(os.environ.get("ASAN_OPTIONS"))
LEASE_S = 2  # the lease of the renewal test: renewed every 0.67 s, scoring takes several


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def stem(name):
    prefix = re.sub(r"[^A-Za-z0-9._-]", "_", name)[:48]
    return (prefix or "trainee") + "-" + hashlib.sha1(name.encode()).hexdigest()[:16]


class Store(StoreFixture):
    """A fresh store (schema made by this Palpa) in its own database."""

    @classmethod
    def prepare_store(cls):
        res = run_cli("store", "init", cls.pg.url(cls.DB))
        assert res.returncode == 0, res.stderr

    def session(self, n, **meta):
        return with_meta(self.small, self.path("s%d.palpa" % n), id=self.new_id(n), **meta)

    def admin(self, sql):
        return self.pg.sql(sql, self.DB)

    def worker(self, *extra, timeout=600):
        return run_cli("batch", "--store", self.pg.url(self.DB, "worker"), "--worker", "--jobs", "1", *extra,
                       timeout=timeout)


class Amplification(Store):
    DB = "amplify"

    def test_numbers_whose_text_is_far_larger_than_stored_are_refused(self):
        before = self.state()
        huge_scale = "('1.' || repeat('0', 16383))::numeric"
        attacks = {
            "case": ["jsonb_build_object('a', %s)" % huge_scale, "'{\"a\": 1e20}'::jsonb", "'{\"a\": 1e-50}'::jsonb",
                     # 20 000 numbers of 23 stored bytes and 16 kB of text each: 330 MB as text.
                     "(SELECT jsonb_object_agg('k' || g, %s) FROM generate_series(1, 20000) g)" % huge_scale],
            "events": ["jsonb_build_array(%s)" % huge_scale],
        }
        n = 0
        for field, values in attacks.items():
            for value in values:
                n += 1
                start = time.monotonic()
                res = self.call_push(**{field: value, "id": literal(self.new_id(100 + n))})
                self.assertNotEqual(res.returncode, 0, value)
                self.assertIn("field %s: holds a number of 1e15 or more, or with more than 40 decimals" % field,
                              res.stderr)
                self.assertLess(time.monotonic() - start, 30.0, value)
        self.assertEqual(self.state(), before)

    def test_a_case_with_ordinary_numbers_is_stored(self):
        res = self.push("station_1", "room-1", self.session(200))
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("stored: ", res.stdout)
        # Rounding noise (cos 90 degrees) is an ordinary number too.
        res = self.call_push(case="'{\"a\": 6.123233995736766e-17}'::jsonb", id=literal(self.new_id(210)),
                             user="station_2", station=literal("room-2"))
        self.assertEqual(res.returncode, 0, res.stderr)


class Names(Store):
    DB = "names"

    def test_look_alike_names_are_refused(self):
        before = self.state()
        for k, name in enumerate(["alice ", " alice", "al  ice", "al\u00a0ice", "\u0430lice", "e\u0301va",
                                  "a" + "\u0301" * 100, "x" + "\u0301" * 3, "\uff41lice", "\u03b1lice",
                                  "\u0251lice", "\u0585lice", "alice\U0001D173", "alice\U0001BCA0", "alice\u2800",
                                  "\uA4EElice", "a\uA4E1ice", "\u2C9Elice", "a\u01C0ice", "alice\u0600",
                                  "a\u05B0\u05B1\u05B2\u05B3\u05B4lice"]):
            res = self.call_push(trainee=literal(name), id=literal(self.new_id(300 + k)))
            self.assertNotEqual(res.returncode, 0, repr(name))
            self.assertIn("field trainee", res.stderr, repr(name))
        for station in ("room-1 ", "room  1"):
            res = self.call_push(station=literal(station), id=literal(self.new_id(320)))
            self.assertIn("field station", res.stderr, repr(station))
        self.assertEqual(self.state(), before)
        # A name a version-2 store took (decomposed) still receives its trainee's sessions.
        self.admin("INSERT INTO trainees(name) VALUES (E'e\\u0301va')")
        res = self.call_push(trainee=literal("e\u0301va"), id=literal(self.new_id(325)), user="station_2",
                             station=literal("room-2"))
        self.assertEqual(res.returncode, 0, res.stderr)
        # Names in one script, accents composed, are welcome.
        for k, name in enumerate(["\u00e9lodie", "\u0410\u043d\u043d\u0430", "Jos\u00e9 Mar\u00eda"]):
            res = self.call_push(trainee=literal(name), id=literal(self.new_id(330 + k)), user="station_2",
                                 station=literal("room-2"))
            self.assertEqual(res.returncode, 0, res.stderr)

    def test_start_dates_ahead_of_the_servers_clock_are_refused(self):
        before = self.state()
        for k, ahead in enumerate(["interval '16 hours'", "interval '10 minutes'"]):
            res = self.call_push(started="now() + " + ahead, id=literal(self.new_id(340 + k)))
            self.assertIn("field started_at: not between 2000-01-01 and the server's clock plus 300 s", res.stderr)
        self.assertEqual(self.state(), before)


class Quotas(Store):
    DB = "quotas"

    def tearDown(self):
        self.admin("UPDATE store_settings SET max_pending_per_login = DEFAULT, max_bytes_per_login_day = DEFAULT, "
                   "max_file_bytes = DEFAULT")

    def test_a_login_over_its_pending_quota_waits_in_its_outbox(self):
        pending = int(self.admin("SELECT count(*) FROM work_queue WHERE login = 'station_2' AND NOT done"))
        self.admin("UPDATE store_settings SET max_pending_per_login = %d" % (pending + 2))
        files = [self.session(400 + k) for k in range(3)]
        res = self.push("station_2", "room-2", *files)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertEqual(res.stdout.count("stored: "), 2, res.stdout)
        self.assertEqual(res.stdout.count("queued: "), 1, res.stdout)
        self.assertIn("quota: this login has %d sessions waiting to be scored" % (pending + 2), res.stdout)
        self.assertEqual(self.admin("SELECT count(*) FROM sessions WHERE uploaded_by = 'station_2'"), str(pending + 2))
        # Once the worker has scored them, the queued one goes.
        self.assertEqual(self.worker().returncode, 0)
        again = self.push("station_2", "room-2", "--outbox-only")
        self.assertIn("outbox: 1 sent, 0 waiting", again.stdout, again.stdout + again.stderr)

    def test_a_login_over_its_daily_bytes_is_refused_and_nothing_changes(self):
        others = "SELECT string_agg(session_id, ',' ORDER BY id) FROM sessions WHERE uploaded_by <> 'station_evil'"
        before = self.admin(others)
        # The day must hold a file at least: the settings refuse less.
        bad = self.pg.psql("UPDATE store_settings SET max_bytes_per_login_day = 65536", self.DB, check=False)
        self.assertIn("store_settings_day_holds_a_file", bad.stderr)
        self.admin("UPDATE store_settings SET max_file_bytes = 65536, max_bytes_per_login_day = 65536")
        files = [self.session(410 + k) for k in range(3)]
        # A push costs its file and its events (the case is stored already).
        events = int(self.admin("SELECT pg_column_size(events) FROM sessions ORDER BY id LIMIT 1"))
        fit = 65536 // (os.path.getsize(files[0]) + events)
        self.assertLess(fit, 3)
        res = self.push("station_evil", "room-evil", *files)
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("quota: this login pushed", res.stdout)
        self.assertEqual(res.stdout.count("stored: "), fit, res.stdout)
        self.assertEqual(res.stdout.count("queued: "), 3 - fit, res.stdout)
        self.assertEqual(self.admin("SELECT count(*) FROM sessions WHERE uploaded_by = 'station_evil'"), str(fit))
        self.assertEqual(self.admin(others), before)


class Fairness(Store):
    DB = "fair"

    def test_a_flood_from_one_login_delays_another_by_one_scoring(self):
        flood = [self.session(500 + k) for k in range(8)]
        self.assertEqual(self.push("station_1", "room-1", *flood).returncode, 0)
        late = [self.session(520 + k) for k in range(2)]
        self.assertEqual(self.push("station_2", "room-2", *late).returncode, 0)
        logins = int(self.admin("SELECT count(DISTINCT login) FROM work_queue WHERE NOT done"))
        self.assertEqual(self.worker().returncode, 0)
        order = self.admin("SELECT s.uploaded_by FROM scores sc JOIN sessions s ON s.id = sc.session_id "
                           "ORDER BY sc.id").split()
        positions = [k + 1 for k, login in enumerate(order) if login == "station_2"]
        self.assertEqual(len(positions), 2, order)
        # In first-in first-out order they would have been 10th and 11th.
        for k, position in enumerate(positions, start=1):
            self.assertLessEqual(position, logins * k, order)

    def test_the_lease_is_renewed_while_a_long_session_is_scored(self):
        if SANITIZED:
            self.skipTest("a sanitized scorer is ten times slower; the release suite runs this")
        long_file = self.path("long.palpa")
        write_constant_session(long_file, hostile.REPO, 64_000_000)
        self.assertEqual(self.push("station_1", "room-1", with_meta(long_file, self.path("long-id.palpa"),
                                                                   id=self.new_id(540))).returncode, 0)
        args = [hostile.CLI, "batch", "--store", self.pg.url(self.DB, "worker"), "--worker", "--jobs", "1",
                "--lease", str(LEASE_S)]
        start = time.monotonic()
        workers = [subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                    env=self.pg.env()) for _ in range(2)]
        outputs = [w.communicate(timeout=600) for w in workers]
        elapsed = time.monotonic() - start
        self.assertGreater(elapsed, 2 * LEASE_S, "the session scored too fast to outlast its lease")
        for w, (out, err) in zip(workers, outputs):
            self.assertEqual(w.returncode, 0, err)
            self.assertNotIn("lost the lease", out)
        row = self.admin("SELECT w.attempts || ' ' || (SELECT count(*) FROM scores sc WHERE sc.session_id = w.session_id) "
                         "FROM work_queue w JOIN sessions s ON s.id = w.session_id WHERE s.session_id = '%s'"
                         % self.new_id(540))
        self.assertEqual(row, "1 1")


class PendingReports(Store):
    DB = "pending"

    def test_the_coordinator_reports_pending_sessions_without_scoring_them(self):
        if SANITIZED:
            self.skipTest("a sanitized report takes no address-space limit; the release suite runs this")
        heavy = self.path("heavy.palpa")
        write_constant_session(heavy, hostile.REPO, 72_000_000)
        heavy = with_meta(heavy, self.path("heavy-id.palpa"), id=self.new_id(600))
        self.assertEqual(self.push("station_evil", "room-evil", heavy).returncode, 0)
        out = self.path("report")

        def limited():  # scoring 72 million ticks in this process would need about 7 GB
            resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))

        pending = int(self.admin("SELECT count(*) FROM work_queue WHERE NOT done"))
        scored = int(self.admin("SELECT count(*) FROM scores"))
        start = time.monotonic()
        res = subprocess.run([hostile.CLI, "batch", "--store", self.pg.url(self.DB, "coord"), "--out", out],
                             capture_output=True, text=True, env=self.pg.env(), preexec_fn=limited, timeout=300)
        self.assertLess(time.monotonic() - start, 60.0)
        self.assertIn(res.returncode, (0, 2), res.stderr)
        self.assertIn("%d pending (not scored by a worker yet)" % pending, res.stderr)
        rows = read_csv(os.path.join(out, "summary.csv"))
        self.assertEqual(len(rows), scored)
        self.assertNotIn(self.new_id(600), [r["session_id"] for r in rows])
        with open(os.path.join(out, "cohort.html")) as fh:
            self.assertIn("not scored by a worker yet (pending)", fh.read())
        self.assertEqual(len(hostile.files_in(os.path.join(out, "stored"))), scored)
        # Scored by a worker, a session is reported from its stored score: never scored again.
        self.admin("UPDATE work_queue w SET done = true, last_error = 'set aside by the test' FROM sessions s "
                   "WHERE s.id = w.session_id AND s.session_id = '%s'" % self.new_id(600))
        self.assertEqual(self.worker().returncode, 0)
        self.admin("UPDATE scores SET result = jsonb_set(result, '{coverage}', '0.123456')")
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out + "-2", "--reports")
        self.assertIn(res.returncode, (0, 2), res.stderr)
        rows = read_csv(os.path.join(out + "-2", "summary.csv"))
        self.assertEqual(len(rows), int(self.admin("SELECT count(*) FROM scores")))
        self.assertEqual({r["coverage"] for r in rows}, {"0.123"}, rows)

    def test_a_long_stored_session_costs_its_page_no_pass_over_its_samples(self):
        long_file = self.path("long.palpa")
        write_constant_session(long_file, hostile.REPO, 2_000_000)
        self.assertEqual(self.push("station_2", "room-2", with_meta(long_file, self.path("long-id.palpa"),
                                                                   id=self.new_id(620))).returncode, 0)
        self.assertEqual(self.worker().returncode, 0)
        out = self.path("long-pages")
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out, "--reports", "--all-modes")
        self.assertIn(res.returncode, (0, 2), res.stderr)
        noted = []
        for name in os.listdir(os.path.join(out, "sessions")):
            if name.endswith(".html"):
                with open(os.path.join(out, "sessions", name), encoding="utf-8") as fh:
                    if "force plot not drawn: 2000000 samples" in fh.read():
                        noted.append(name)
        self.assertEqual(len(noted), 1, noted)

    def test_session_pages_escape_every_field_of_the_file(self):
        evil = with_meta(self.small, self.path("fields.palpa"), id=self.new_id(610), device="dev\x1b[2J\u202eice",
                         software_version="1.0\x07<script>", case_source="/cases/\u202egnp.json")
        self.assertEqual(self.push("station_2", "room-2", evil).returncode, 0)
        self.assertEqual(self.worker().returncode, 0)
        out = self.path("pages")
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out, "--reports")
        self.assertIn(res.returncode, (0, 2), res.stderr)
        pages = [os.path.join(out, "sessions", n) for n in os.listdir(os.path.join(out, "sessions"))
                 if n.endswith(".html")]
        self.assertTrue(pages)
        for page in pages:
            with open(page, encoding="utf-8") as fh:
                html = fh.read()
            for bad in ("\x1b", "\x07", "\u202e", "<script>"):
                self.assertNotIn(bad, html, page)


class Enrolment(Store):
    DB = "enrol"

    def tearDown(self):
        self.admin("UPDATE store_settings SET enrolment = DEFAULT")

    def test_a_forged_attempt_is_flagged_and_left_out_of_the_curves(self):
        own = [self.session(700 + k, trainee="tina") for k in range(2)]
        self.assertEqual(self.push("station_1", "room-1", *own).returncode, 0)
        forged = [self.session(710 + k, trainee="tina") for k in range(2)]
        res = self.push("station_evil", "room-evil", *forged)
        self.assertEqual(res.returncode, 0, res.stderr)  # stored, so a coordinator sees it, and flagged
        self.assertEqual(self.admin("SELECT count(*) FROM sessions s JOIN trainees t ON t.id = s.trainee_id "
                                    "WHERE NOT s.enrolled AND t.name = 'tina'"), "2")
        self.assertEqual(self.worker().returncode, 0)
        out = self.path("report")
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out, "--all-modes")
        self.assertIn(res.returncode, (0, 2), res.stderr)
        # Who is the intruder? The first push proves nothing: no attempt of tina counts yet.
        self.assertFalse(os.path.exists(os.path.join(out, "trainees", stem("tina") + ".csv")))
        with open(os.path.join(out, "cohort.html")) as fh:
            html = fh.read()
        self.assertIn("Flagged: trainee tina was pushed from stations room-1, room-evil", html)
        self.assertEqual(len([r for r in read_csv(os.path.join(out, "summary.csv")) if r["trainee"] == "tina"]), 4)
        enrol = run_cli("store", "enrol", "tina", "--station", "room-1", "--store", self.pg.url(self.DB, "coord"))
        self.assertEqual(enrol.returncode, 0, enrol.stderr)
        self.assertIn("enrolled: trainee tina at station room-1\n", enrol.stdout)  # confirmed, not "already so"
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out + "-2", "--all-modes")
        curve = read_csv(os.path.join(out + "-2", "trainees", stem("tina") + ".csv"))
        self.assertEqual([a["station"] for a in curve], ["room-1", "room-1"])
        with open(os.path.join(out + "-2", "cohort.html")) as fh:
            html = fh.read()
        self.assertIn("sessions were pushed by a station the trainee is not enrolled at", html)
        self.assertIn("trainee tina from station room-evil", html)

    def test_a_trainee_first_pushed_by_an_intruder_counts_for_no_one(self):
        # The intruder pushes a trainee id before its own station does (ids are guessable).
        first = [self.session(750 + k, trainee="vera") for k in range(2)]
        self.assertEqual(self.push("station_evil", "room-evil", *first).returncode, 0)
        own = [self.session(760 + k, trainee="vera") for k in range(2)]
        self.assertEqual(self.push("station_1", "room-1", *own).returncode, 0)
        self.assertEqual(self.worker().returncode, 0)
        out = self.path("vera")
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out, "--all-modes")
        self.assertIn(res.returncode, (0, 2), res.stderr)
        with open(os.path.join(out, "cohort.html")) as fh:
            html = fh.read()
        self.assertIn("Flagged: trainee vera was pushed from stations room-1, room-evil and no coordinator enrolled "
                      "them at any", html)
        self.assertFalse(os.path.exists(os.path.join(out, "trainees", stem("vera") + ".csv")))
        # A coordinator says whose the trainee is: that station's attempts count, the other's are flagged.
        enrol = run_cli("store", "enrol", "vera", "--station", "room-1", "--store", self.pg.url(self.DB, "coord"))
        self.assertEqual(enrol.returncode, 0, enrol.stderr)
        res = run_cli("batch", "--store", self.pg.url(self.DB, "coord"), "--out", out + "-2", "--all-modes")
        self.assertIn(res.returncode, (0, 2), res.stderr)
        curve = read_csv(os.path.join(out + "-2", "trainees", stem("vera") + ".csv"))
        self.assertEqual([a["station"] for a in curve], ["room-1", "room-1"])

    def test_refusing_unenrolled_pushes_says_the_same_for_every_name(self):
        self.assertEqual(self.push("station_1", "room-1", self.session(720, trainee="uma")).returncode, 0)
        self.admin("UPDATE store_settings SET enrolment = 'refuse'")
        before = self.state()
        messages = []
        for k, name in enumerate(["uma", "nobody-%d" % time.time_ns()]):
            res = self.call_push(trainee=literal(name), id=literal(self.new_id(730 + k)))
            self.assertNotEqual(res.returncode, 0)
            messages.append(re.sub(r"^.*ERROR:\s*", "", res.stderr.strip().splitlines()[0]))
        self.assertEqual(messages[0], messages[1])
        self.assertIn('field trainee: not enrolled at station "room-evil"', messages[0])
        self.assertEqual(self.state(), before)
        enrol = run_cli("store", "enrol", "uma", "--station", "room-evil", "--store", self.pg.url(self.DB, "coord"))
        self.assertEqual(enrol.returncode, 0, enrol.stderr)
        self.assertIn("enrolled: trainee uma at station room-evil", enrol.stdout)
        res = self.call_push(trainee=literal("uma"), id=literal(self.new_id(740)))
        self.assertEqual(res.returncode, 0, res.stderr)
        # Stations may not enrol.
        res = self.sql("SELECT public.palpa_enrol('uma', 'room-1', true);", "station_evil", check=False)
        self.assertIn("permission denied", res.stderr)


class Locks(Store):
    DB = "locks"

    def test_a_transaction_a_station_holds_open_delays_a_push_by_seconds_and_it_is_queued(self):
        evil = subprocess.Popen([os.path.join(self.pg.bin, "psql"), "-X", "-q", "-d",
                                 self.pg.url(self.DB, "station_evil")],
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                env=self.pg.env())
        try:
            # The new trainee's row and the new case's row, held in an open transaction.
            fresh = json.loads(hostile.meta_of(self.small)["case"])
            fresh["title"] = "A case no one has pushed yet"
            case = json.dumps(fresh)
            push = ("SELECT * FROM public.palpa_push_session('room-evil', '%s', 'newcomer', '', %s::jsonb, now(), "
                    "'trainee', true, 1, 'x.palpa', '[]'::jsonb, '\\x%s'::bytea);"
                    % (self.new_id(800), literal(case), hostile.SQLITE_HEADER))
            evil.stdin.write("SET idle_in_transaction_session_timeout = 0; SET statement_timeout = 0; "
                             "SET lock_timeout = 0;\nSELECT pg_advisory_lock(1346457676);\nBEGIN;\n" + push + "\n")
            evil.stdin.flush()
            for _ in range(100):
                if self.admin("SELECT count(*) FROM pg_stat_activity WHERE usename = 'station_evil' "
                              "AND state = 'idle in transaction'") == "1":
                    break
                time.sleep(0.1)
            else:
                self.fail("the station's transaction did not open")
            start = time.monotonic()
            res = self.push("station_2", "room-2", self.session(810, trainee="newcomer"))
            self.assertLess(time.monotonic() - start, 30.0)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertIn("queued: ", res.stdout)
            self.assertIn("lock", res.stdout)
            # The same case for another trainee: nothing to wait on.
            start = time.monotonic()
            res = self.push("station_2", "room-2", self.session(820, trainee="someone-else", case=case),
                            outbox=self.path("outbox-empty"))  # not the outbox that waits on the held trainee
            self.assertIn("stored: ", res.stdout, res.stdout + res.stderr)
            self.assertLess(time.monotonic() - start, 4.0)
            start = time.monotonic()
            init = run_cli("store", "init", self.pg.url(self.DB))
            self.assertEqual(init.returncode, 0, init.stderr)
            self.assertIn("already up to date", init.stdout)
            self.assertLess(time.monotonic() - start, 30.0)
        finally:
            evil.communicate(timeout=60)  # closes its input: psql ends, and its transaction with it
        again = self.push("station_2", "room-2", "--outbox-only")
        self.assertIn("outbox: 1 sent, 0 waiting", again.stdout, again.stdout + again.stderr)


class CentreSetup(Store):
    """docs/centre.md, section 1, as written: an administrator with CREATEROLE who is not a
    superuser owns the database and runs store init; the superuser's one statement there
    takes large objects away from everyone else."""

    DB = "centre_probe"

    def test_a_non_superuser_administrator_and_large_objects(self):
        pg = self.pg
        with open(os.path.join(hostile.REPO, "docs", "centre.md")) as fh:
            doc = fh.read()
        commands = ["sudo -u postgres createuser --createrole --pwprompt palpa_admin",
                    "sudo -u postgres createdb --owner=palpa_admin palpa",
                    'sudo -u postgres psql -d palpa -c "REVOKE EXECUTE ON FUNCTION lo_create(oid), lo_creat(integer), '
                    'lo_from_bytea(oid, bytea), lo_import(text), lo_import(text, oid) FROM PUBLIC"']
        for command in commands:
            self.assertIn(command, doc)
        # The same commands against the test server, whose superuser is named palpa_admin:
        # the centre's administrator is centre_admin here.
        pg.add_login("centre_admin", "pg_read_all_settings")
        pg.sql("ALTER ROLE centre_admin CREATEROLE NOSUPERUSER")
        pg.sql("CREATE DATABASE centre OWNER centre_admin")
        pg.sql("CREATE DATABASE centre_open OWNER centre_admin")
        res = run_cli("store", "init", pg.url("centre_open", "centre_admin"))
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("warning: any login can create large objects in this database", res.stderr)
        pg.sql("REVOKE EXECUTE ON FUNCTION lo_create(oid), lo_creat(integer), lo_from_bytea(oid, bytea), "
               "lo_import(text), lo_import(text, oid) FROM PUBLIC", "centre")
        res = run_cli("store", "init", pg.url("centre", "centre_admin"))
        self.assertEqual(res.returncode, 0, res.stderr)
        self.assertIn("schema version 3 (was 0)", res.stdout)
        self.assertNotIn("large objects", res.stderr)
        self.assertEqual(pg.sql("SELECT rolsuper FROM pg_roles WHERE rolname = 'centre_admin'"), "f")
        self.assertEqual(pg.sql("SELECT tableowner FROM pg_tables WHERE tablename = 'sessions'", "centre"),
                         "palpa_owner")
        for call in ("lo_create(0)", "lo_from_bytea(0, '\\x00')"):
            r = pg.psql("SELECT %s" % call, "centre", "station_1", check=False)
            self.assertIn("permission denied", r.stderr, call)
        pushed = run_cli("store", "push", with_meta(self.small, os.path.join(self.dir, "c.palpa"),
                                                    id="c" * 32),
                         "--store", pg.url("centre", "station_1"), "--station", "room-1",
                         "--outbox", os.path.join(self.dir, "outbox-centre"))
        self.assertEqual(pushed.returncode, 0, pushed.stderr)
        self.assertIn("stored: ", pushed.stdout)


def tearDownModule():
    hostile.tearDownModule()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--repo", required=True)
    args, rest = ap.parse_known_args()
    hostile.CLI, hostile.REPO = os.path.abspath(args.cli), os.path.abspath(args.repo)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
