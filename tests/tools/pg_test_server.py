#!/usr/bin/python3
"""A throwaway PostgreSQL server for tests: initdb under a temporary folder, listening on
127.0.0.1 at a free port, scram-sha-256 authentication with an admin password in a
pgpass file of its own (never on a command line), stopped and removed on exit.

    with PgServer() as pg:
        env = pg.env()              # PGPASSFILE for the admin and the logins it creates
        pg.url("palpa")             # "host=127.0.0.1 port=N dbname=palpa user=palpa_admin"
        pg.sql("CREATE DATABASE palpa")
        pg.add_login("station_a", "palpa_station")

initdb and postgres refuse to run as root: when the euid is 0 (CI) they run as the
`postgres` system user (runuser), the temporary folder chowned to it.

    /usr/bin/python3 tests/tools/pg_test_server.py    # start one, print its URL, wait for Ctrl-C

unavailable_reason() says why no server can be started here (None when one can); tests
skip with it locally and fail with it when CI=true.
"""
import os
import pwd
import secrets
import shutil
import socket
import subprocess
import sys
import tempfile

BIN_DIRS = ["/usr/lib/postgresql/15/bin", "/usr/lib/postgresql/16/bin", "/usr/lib/postgresql/14/bin"]


def find_bin():
    for d in BIN_DIRS:
        if os.path.exists(os.path.join(d, "initdb")) and os.path.exists(os.path.join(d, "pg_ctl")):
            return d
    found = shutil.which("initdb")
    return os.path.dirname(found) if found else None


def unavailable_reason():
    if find_bin() is None:
        return "PostgreSQL server binaries (initdb, pg_ctl) not found: apt-get install postgresql"
    if shutil.which("psql") is None and not os.path.exists(os.path.join(find_bin(), "psql")):
        return "psql not found: apt-get install postgresql-client"
    if os.geteuid() == 0:
        try:
            pwd.getpwnam("postgres")
        except KeyError:
            return "running as root and there is no 'postgres' user to run the server as"
    return None


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class PgServer:
    ADMIN = "palpa_admin"

    def __init__(self):
        self.bin = find_bin()
        self.root = None
        self.port = None
        self.running = False
        self.passwords = {}

    # -- lifecycle -------------------------------------------------------------------
    def __enter__(self):
        self.start_new()
        return self

    def __exit__(self, *exc):
        self.close()

    def _as_server_user(self, argv):
        if os.geteuid() == 0:
            return ["runuser", "-u", "postgres", "--"] + argv
        return argv

    def _run(self, argv, **kw):
        return subprocess.run(self._as_server_user(argv), check=True, capture_output=True, text=True, **kw)

    def start_new(self):
        self.root = tempfile.mkdtemp(prefix="palpa-pg-")
        self.data = os.path.join(self.root, "data")
        self.sockets = os.path.join(self.root, "sockets")
        os.mkdir(self.sockets)
        admin_password = secrets.token_hex(16)
        pwfile = os.path.join(self.root, "pwfile")
        with open(pwfile, "w") as f:
            f.write(admin_password + "\n")
        if os.geteuid() == 0:
            pw = pwd.getpwnam("postgres")
            for p in (self.root, self.sockets, pwfile):
                os.chown(p, pw.pw_uid, pw.pw_gid)
        self._run([os.path.join(self.bin, "initdb"), "-D", self.data, "-U", self.ADMIN, "--auth=scram-sha-256",
                   "--pwfile=" + pwfile, "-E", "UTF8", "--locale=C"])
        os.remove(pwfile)
        self.pgpass = os.path.join(self.root, "pgpass")  # owned by the test's user, read by libpq
        self.passwords[self.ADMIN] = admin_password
        self._write_pgpass()
        self.port = free_port()
        self.start()

    def start(self):
        opts = "-c listen_addresses=127.0.0.1 -p %d -k %s -c fsync=off -c full_page_writes=off" % (self.port, self.sockets)
        self._run([os.path.join(self.bin, "pg_ctl"), "-D", self.data, "-o", opts, "-l",
                   os.path.join(self.data, "server.log"), "-w", "-t", "60", "start"])
        self.running = True

    def stop(self):
        if self.running:
            self._run([os.path.join(self.bin, "pg_ctl"), "-D", self.data, "-m", "fast", "-w", "stop"])
            self.running = False

    def close(self):
        try:
            self.stop()
        finally:
            if self.root:
                shutil.rmtree(self.root, ignore_errors=True)
                self.root = None

    def log(self):
        try:
            with open(os.path.join(self.data, "server.log")) as f:
                return f.read()
        except OSError as e:
            return str(e)

    # -- access ----------------------------------------------------------------------
    def _write_pgpass(self):
        with open(self.pgpass, "w") as f:
            for user, password in self.passwords.items():
                f.write("127.0.0.1:*:*:%s:%s\n" % (user, password))
        os.chmod(self.pgpass, 0o600)

    def env(self, **extra):
        env = dict(os.environ)
        env["PGPASSFILE"] = self.pgpass
        for k in ("PGHOST", "PGPORT", "PGUSER", "PGDATABASE", "PGPASSWORD", "PGSERVICE", "PALPA_STORE", "PALPA_STATION"):
            env.pop(k, None)
        env.update(extra)
        return env

    def url(self, dbname="postgres", user=None):
        return "host=127.0.0.1 port=%d dbname=%s user=%s" % (self.port, dbname, user or self.ADMIN)

    def psql(self, sql, dbname="postgres", user=None, check=True):
        psql = os.path.join(self.bin, "psql")
        return subprocess.run([psql, "-X", "-q", "-A", "-t", "-v", "ON_ERROR_STOP=1", "-d", self.url(dbname, user),
                               "-c", sql], capture_output=True, text=True, env=self.env(), check=check)

    def psql_stdin(self, sql, dbname="postgres", user=None, check=True):
        """Like psql() with the SQL on standard input: for statements too long for a command
        line (large literals) and for text with control characters."""
        psql = os.path.join(self.bin, "psql")
        return subprocess.run([psql, "-X", "-q", "-A", "-t", "-v", "ON_ERROR_STOP=1", "-d", self.url(dbname, user)],
                              input=sql, capture_output=True, text=True, env=self.env(), check=check)

    def sql(self, sql, dbname="postgres", user=None):
        return self.psql(sql, dbname, user).stdout.strip()

    def add_login(self, user, group, dbname="postgres"):
        """Creates LOGIN role `user` in `group` with a random password kept in the pgpass file."""
        password = secrets.token_hex(12)
        self.passwords[user] = password
        self._write_pgpass()
        # psql's \password would prompt; a literal in SQL given on stdin never reaches a command line.
        psql = os.path.join(self.bin, "psql")
        subprocess.run([psql, "-X", "-q", "-v", "ON_ERROR_STOP=1", "-d", self.url(dbname)], check=True,
                       capture_output=True, text=True, env=self.env(),
                       input="CREATE ROLE %s LOGIN PASSWORD '%s' IN ROLE %s;\n" % (user, password, group))


def server_for_tests():
    """A started PgServer, or unittest.SkipTest when PostgreSQL is not installed here; under
    CI=true a missing server is a failure (RuntimeError), never a skip."""
    import unittest
    reason = unavailable_reason()
    if reason and os.environ.get("CI", "").lower() == "true":
        raise RuntimeError("CI=true and no PostgreSQL test server: " + reason)
    if reason:
        raise unittest.SkipTest(reason)
    pg = PgServer()
    try:
        pg.start_new()
    except subprocess.CalledProcessError as e:
        log = pg.log() if pg.root else ""
        pg.close()
        raise RuntimeError("PostgreSQL test server did not start: %s\n%s\n%s" % (e, e.stderr, log))
    return pg


def main():
    reason = unavailable_reason()
    if reason:
        print("pg_test_server: " + reason, file=sys.stderr)
        return 1
    with PgServer() as pg:
        print("PGPASSFILE=%s" % pg.pgpass)
        print(pg.url())
        sys.stdout.flush()
        try:
            input()
        except (KeyboardInterrupt, EOFError):
            pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
