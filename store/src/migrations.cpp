// The centre store's schema, one migration per entry (docs/centre.md, "Schema"). Constant
// SQL only: values never appear here, they travel as statement parameters.
#include "migrations.hpp"

namespace palpa::store {
namespace {

// Version 1: the tables, the work queue, the three group roles and what each may do.
// Stations add sessions only through palpa_push_session (SECURITY DEFINER) and see their
// own uploads through the view station_sessions; they have no privilege on the tables.
constexpr const char* kV1Tables = R"sql(
CREATE TABLE stations (
  name text PRIMARY KEY,
  db_user text NOT NULL,
  first_seen timestamptz NOT NULL DEFAULT now());
CREATE TABLE trainees (
  id bigserial PRIMARY KEY,
  name text NOT NULL UNIQUE);
CREATE TABLE cases (
  id bigserial PRIMARY KEY,
  sha256 text NOT NULL UNIQUE,
  title text NOT NULL DEFAULT '',
  document jsonb NOT NULL);
CREATE TABLE sessions (
  id bigserial PRIMARY KEY,
  session_id text NOT NULL UNIQUE,
  station text NOT NULL REFERENCES stations(name),
  trainee_id bigint NOT NULL REFERENCES trainees(id),
  case_id bigint NOT NULL REFERENCES cases(id),
  started_at timestamptz NOT NULL,
  mode text NOT NULL,
  complete boolean NOT NULL,
  samples bigint NOT NULL,
  size_bytes bigint NOT NULL,
  sha256 text NOT NULL,
  file_name text NOT NULL,
  events jsonb NOT NULL,
  file bytea NOT NULL,
  uploaded_by text NOT NULL,
  uploaded_at timestamptz NOT NULL DEFAULT now());
CREATE INDEX sessions_uploaded_by ON sessions(uploaded_by);
CREATE INDEX sessions_started_at ON sessions(started_at);
CREATE TABLE scores (
  id bigserial PRIMARY KEY,
  session_id bigint NOT NULL REFERENCES sessions(id),
  scorer_version text NOT NULL,
  thresholds_sha256 text NOT NULL,
  score double precision NOT NULL,
  passed boolean NOT NULL,
  result jsonb NOT NULL,
  scored_at timestamptz NOT NULL DEFAULT now(),
  worker text NOT NULL,
  UNIQUE (session_id, scorer_version, thresholds_sha256));
CREATE TABLE work_queue (
  session_id bigint PRIMARY KEY REFERENCES sessions(id),
  done boolean NOT NULL DEFAULT false,
  lease_owner text,
  lease_expires timestamptz,
  attempts integer NOT NULL DEFAULT 0,
  last_error text);
CREATE INDEX work_queue_pending ON work_queue(session_id) WHERE NOT done;
CREATE VIEW station_sessions AS
  SELECT s.session_id, s.station, t.name AS trainee, s.started_at, s.mode, s.complete, s.samples,
         s.size_bytes, s.sha256, s.file_name, s.uploaded_at
  FROM sessions s JOIN trainees t ON t.id = s.trainee_id
  WHERE s.uploaded_by = session_user;
)sql";

constexpr const char* kV1Push = R"sql(
CREATE FUNCTION palpa_push_session(p_station text, p_session_id text, p_trainee text, p_case_sha256 text,
    p_case_title text, p_case jsonb, p_started_at timestamptz, p_mode text, p_complete boolean,
    p_samples bigint, p_file_name text, p_events jsonb, p_file bytea)
  RETURNS TABLE (stored boolean, server_sha256 text)
  LANGUAGE plpgsql SECURITY DEFINER SET search_path = pg_catalog, public AS $fn$
DECLARE
  v_owner text;
  v_sha text;
  v_trainee bigint;
  v_case bigint;
  v_id bigint;
BEGIN
  INSERT INTO stations(name, db_user) VALUES (p_station, session_user) ON CONFLICT (name) DO NOTHING;
  SELECT st.db_user INTO v_owner FROM stations st WHERE st.name = p_station;
  IF v_owner <> session_user THEN
    RAISE EXCEPTION 'station "%" uploads as login "%", not "%"', p_station, v_owner, session_user
      USING ERRCODE = '42501';
  END IF;
  SELECT s.sha256 INTO v_sha FROM sessions s WHERE s.session_id = p_session_id;
  IF FOUND THEN
    RETURN QUERY SELECT false, v_sha;
    RETURN;
  END IF;
  INSERT INTO trainees(name) VALUES (p_trainee) ON CONFLICT (name) DO NOTHING;
  SELECT t.id INTO v_trainee FROM trainees t WHERE t.name = p_trainee;
  INSERT INTO cases(sha256, title, document) VALUES (p_case_sha256, p_case_title, p_case)
    ON CONFLICT (sha256) DO NOTHING;
  SELECT c.id INTO v_case FROM cases c WHERE c.sha256 = p_case_sha256;
  INSERT INTO sessions(session_id, station, trainee_id, case_id, started_at, mode, complete, samples,
                       size_bytes, sha256, file_name, events, file, uploaded_by)
    VALUES (p_session_id, p_station, v_trainee, v_case, p_started_at, p_mode, p_complete, p_samples,
            octet_length(p_file), encode(sha256(p_file), 'hex'), p_file_name, p_events, p_file, session_user)
    ON CONFLICT (session_id) DO NOTHING
    RETURNING id INTO v_id;
  IF v_id IS NULL THEN  -- the same session pushed at the same time from elsewhere
    SELECT s.sha256 INTO v_sha FROM sessions s WHERE s.session_id = p_session_id;
    RETURN QUERY SELECT false, v_sha;
    RETURN;
  END IF;
  INSERT INTO work_queue(session_id) VALUES (v_id);
  RETURN QUERY SELECT true, s.sha256 FROM sessions s WHERE s.id = v_id;
END
$fn$;
REVOKE ALL ON FUNCTION palpa_push_session FROM PUBLIC;
)sql";

constexpr const char* kV1Roles = R"sql(
DO $roles$
DECLARE r text;
BEGIN
  FOREACH r IN ARRAY ARRAY['palpa_station', 'palpa_worker', 'palpa_coordinator'] LOOP
    IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = r) THEN
      EXECUTE format('CREATE ROLE %I NOLOGIN', r);
    END IF;
  END LOOP;
END
$roles$;
GRANT SELECT ON palpa_schema TO palpa_station, palpa_worker, palpa_coordinator;
GRANT EXECUTE ON FUNCTION palpa_push_session TO palpa_station, palpa_coordinator;
GRANT SELECT ON station_sessions TO palpa_station, palpa_coordinator;
GRANT SELECT ON sessions, trainees, cases, scores, work_queue TO palpa_worker;
GRANT INSERT ON scores TO palpa_worker;
GRANT USAGE ON SEQUENCE scores_id_seq TO palpa_worker;
GRANT UPDATE ON work_queue TO palpa_worker;
GRANT SELECT ON stations, trainees, cases, sessions, scores, work_queue TO palpa_coordinator;
GRANT UPDATE ON work_queue TO palpa_coordinator;
GRANT palpa_worker TO palpa_coordinator;
)sql";


// Version 2: the store made safe against a hostile station (docs/security.md).
// - Every object belongs to palpa_owner, a NOLOGIN role that cannot create roles: the
//   SECURITY DEFINER function runs with its rights, never the admin's.
// - No role may create temporary tables or objects in public: a station cannot shadow a
//   table the function uses (PostgreSQL manual, CREATE FUNCTION, "Writing SECURITY DEFINER
//   Functions Safely"). The function also pins search_path with pg_temp last and names
//   every table with its schema, so it would stay safe if TEMP were granted again.
// - The push function checks every value it stores and computes the case key itself.
constexpr const char* kV2Owner = R"sql(
DO $owner$
BEGIN
  IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = 'palpa_owner') THEN
    CREATE ROLE palpa_owner NOLOGIN NOSUPERUSER NOCREATEDB NOCREATEROLE NOINHERIT NOREPLICATION;
  END IF;
  -- A non-superuser admin must be able to act as the owner for later migrations.
  IF NOT (SELECT rolsuper FROM pg_roles WHERE rolname = current_user) THEN
    EXECUTE format('GRANT palpa_owner TO %I', current_user);
  END IF;
  EXECUTE format('REVOKE TEMPORARY, CREATE ON DATABASE %I FROM PUBLIC', current_database());
  -- Large objects live outside every table: nobody but the admin may create them here.
  IF (SELECT rolsuper FROM pg_roles WHERE rolname = current_user) THEN
    REVOKE EXECUTE ON FUNCTION pg_catalog.lo_create(oid), pg_catalog.lo_creat(integer),
      pg_catalog.lo_from_bytea(oid, bytea), pg_catalog.lo_import(text), pg_catalog.lo_import(text, oid)
      FROM PUBLIC;
  END IF;
END
$owner$;
REVOKE CREATE ON SCHEMA public FROM PUBLIC;
GRANT USAGE, CREATE ON SCHEMA public TO palpa_owner;
CREATE TABLE public.store_settings (
  one boolean PRIMARY KEY DEFAULT true CHECK (one),
  max_file_bytes bigint NOT NULL DEFAULT 67108864 CHECK (max_file_bytes BETWEEN 4096 AND 1073741824),
  max_score_attempts integer NOT NULL DEFAULT 3 CHECK (max_score_attempts BETWEEN 1 AND 100));
INSERT INTO public.store_settings DEFAULT VALUES;
-- The case key is the server's own hash of the stored document; keys a client chose are
-- replaced, and documents that then share a key become one row.
UPDATE public.cases SET sha256 = 'v1:' || id;
WITH keyed AS (
  SELECT id, min(id) OVER (PARTITION BY document::text) AS keep FROM public.cases)
UPDATE public.sessions s SET case_id = k.keep FROM keyed k WHERE s.case_id = k.id AND k.id <> k.keep;
DELETE FROM public.cases c WHERE EXISTS (SELECT 1 FROM public.cases d WHERE d.document::text = c.document::text
                                                                   AND d.id < c.id);
UPDATE public.cases SET sha256 = encode(sha256(convert_to(document::text, 'UTF8')), 'hex');
ALTER TABLE public.stations OWNER TO palpa_owner;
ALTER TABLE public.trainees OWNER TO palpa_owner;
ALTER TABLE public.cases OWNER TO palpa_owner;
ALTER TABLE public.sessions OWNER TO palpa_owner;
ALTER TABLE public.scores OWNER TO palpa_owner;
ALTER TABLE public.work_queue OWNER TO palpa_owner;
ALTER TABLE public.store_settings OWNER TO palpa_owner;
ALTER VIEW public.station_sessions OWNER TO palpa_owner;
-- A barrier: a station's own WHERE conditions (a function that raises an error naming its
-- argument, say) run only on the rows the view lets it see, never before its filter.
ALTER VIEW public.station_sessions SET (security_barrier = true);
DROP FUNCTION public.palpa_push_session(text, text, text, text, text, jsonb, timestamptz, text, boolean, bigint,
                                        text, jsonb, bytea);
)sql";

// The checks name the field at fault and never echo a value (it may hold control
// characters) nor anything about sessions or logins that are not the caller's.
constexpr const char* kV2Checks = R"sql(
CREATE FUNCTION public.palpa_check_text(p_field text, p_value text, p_max integer)
  RETURNS void LANGUAGE plpgsql IMMUTABLE SET search_path = pg_catalog, pg_temp AS $fn$
BEGIN
  IF p_value IS NULL OR p_value = '' THEN
    RAISE EXCEPTION 'field %: empty', p_field USING ERRCODE = '22023';
  END IF;
  IF pg_catalog.char_length(p_value) > p_max THEN
    RAISE EXCEPTION 'field %: longer than % characters', p_field, p_max USING ERRCODE = '22023';
  END IF;
  -- Controls, bidirectional controls and the invisible (default-ignorable) characters: a
  -- name must look like what it is (no "rο om" with a hidden mark, no reordered text).
  IF p_value ~ ('[\u0001-\u001f\u007f-\u009f\u00ad\u034f\u061c\u115f\u1160\u17b4\u17b5\u180b-\u180f'
                '\u200b-\u200f\u2028-\u202e\u2060-\u206f\u3164\ufe00-\ufe0f\ufeff\uffa0\ufff0-\ufffb'
                '\U000e0000-\U000e0fff]') THEN
    RAISE EXCEPTION 'field %: holds a control, invisible or bidirectional-override character', p_field
      USING ERRCODE = '22023';
  END IF;
END
$fn$;
ALTER FUNCTION public.palpa_check_text(text, text, integer) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_check_text(text, text, integer) FROM PUBLIC;

CREATE FUNCTION public.palpa_check_session(p_session_id text, p_trainee text, p_case_title text, p_case jsonb,
    p_started_at timestamptz, p_mode text, p_complete boolean, p_samples bigint, p_file_name text,
    p_events jsonb, p_file bytea)
  RETURNS void LANGUAGE plpgsql STABLE SET search_path = pg_catalog, pg_temp AS $fn$
DECLARE
  v_max bigint;
  v_huge constant jsonpath := 'strict $.** ? (@.type() == "number" && (@ > 1e308 || @ < -1e308 || '
                              '(@ != 0 && @ < 1e-300 && @ > -1e-300)))';
BEGIN
  IF p_session_id IS NULL OR p_session_id !~ '^([0-9a-f]{32}|[0-9a-f]{16})$' THEN
    RAISE EXCEPTION 'field id: not a session id (32 lowercase hex digits)' USING ERRCODE = '22023';
  END IF;
  PERFORM public.palpa_check_text('trainee', p_trainee, 128);
  PERFORM public.palpa_check_text('file name', p_file_name, 255);
  IF pg_catalog.strpos(p_file_name, '/') > 0 OR p_file_name IN ('.', '..') THEN
    RAISE EXCEPTION 'field file name: holds a /' USING ERRCODE = '22023';
  END IF;
  IF p_case_title IS NULL OR pg_catalog.char_length(p_case_title) > 200 THEN
    RAISE EXCEPTION 'field case title: longer than 200 characters' USING ERRCODE = '22023';
  END IF;
  IF p_case_title <> '' THEN PERFORM public.palpa_check_text('case title', p_case_title, 200); END IF;
  IF p_mode IS NULL OR p_mode NOT IN ('trainee', 'instructor-try', 'scripted', 'replay', 'simulated', 'bench',
                                      'unknown') THEN
    RAISE EXCEPTION 'field mode: not one of trainee, instructor-try, scripted, replay, simulated, bench, unknown'
      USING ERRCODE = '22023';
  END IF;
  IF p_started_at IS NULL OR NOT pg_catalog.isfinite(p_started_at) OR p_started_at < '2000-01-01T00:00:00Z'
     OR p_started_at > pg_catalog.now() + interval '1 day' THEN
    RAISE EXCEPTION 'field started_at: not a date between 2000-01-01 and tomorrow' USING ERRCODE = '22023';
  END IF;
  IF p_complete IS NOT TRUE THEN
    RAISE EXCEPTION 'field complete: the session has no end event' USING ERRCODE = '22023';
  END IF;
  IF p_samples IS NULL OR p_samples < 0 OR p_samples > 72000000 THEN
    RAISE EXCEPTION 'field samples: not between 0 and 72000000' USING ERRCODE = '22023';
  END IF;
  -- Sizes as stored (pg_column_size), and no number a double cannot hold: 1e131071 takes a
  -- few bytes in jsonb and 131072 characters as text, which the case key is computed from.
  IF p_case IS NULL OR pg_catalog.jsonb_typeof(p_case) <> 'object' OR pg_catalog.pg_column_size(p_case) > 16777216
     OR pg_catalog.jsonb_path_exists(p_case, v_huge) THEN
    RAISE EXCEPTION 'field case: not a case document (a JSON object of at most 16 MiB, numbers a double can hold)'
      USING ERRCODE = '22023';
  END IF;
  IF p_events IS NULL OR pg_catalog.jsonb_typeof(p_events) <> 'array'
     OR pg_catalog.pg_column_size(p_events) > 16777216 OR pg_catalog.jsonb_path_exists(p_events, v_huge) THEN
    RAISE EXCEPTION 'field events: not a JSON array of at most 16 MiB (numbers a double can hold)'
      USING ERRCODE = '22023';
  END IF;
  SELECT st.max_file_bytes INTO v_max FROM public.store_settings st;
  IF p_file IS NULL OR pg_catalog.octet_length(p_file) > v_max THEN
    RAISE EXCEPTION 'field file: larger than the store accepts (% bytes; store_settings.max_file_bytes)', v_max
      USING ERRCODE = '22023';
  END IF;
  IF pg_catalog.substr(p_file, 1, 16) <> '\x53514c69746520666f726d6174203300'::bytea THEN
    RAISE EXCEPTION 'field file: not an SQLite database (a Palpa session is one)' USING ERRCODE = '22023';
  END IF;
END
$fn$;
ALTER FUNCTION public.palpa_check_session(text, text, text, jsonb, timestamptz, text, boolean, bigint, text, jsonb,
                                          bytea) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_check_session(text, text, text, jsonb, timestamptz, text, boolean, bigint, text,
                                                  jsonb, bytea) FROM PUBLIC;
)sql";

constexpr const char* kV2Push = R"sql(
CREATE FUNCTION public.palpa_push_session(p_station text, p_session_id text, p_trainee text, p_case_title text,
    p_case jsonb, p_started_at timestamptz, p_mode text, p_complete boolean, p_samples bigint, p_file_name text,
    p_events jsonb, p_file bytea)
  RETURNS TABLE (stored boolean, server_sha256 text)
  LANGUAGE plpgsql SECURITY DEFINER SET search_path = pg_catalog, public, pg_temp AS $fn$
DECLARE
  v_owner text;
  v_by text;
  v_sha text;
  v_case_sha text;
  v_trainee bigint;
  v_case bigint;
  v_id bigint;
BEGIN
  PERFORM public.palpa_check_text('station', p_station, 64);
  IF p_station !~ '^[A-Za-z0-9][A-Za-z0-9 ._-]*$' THEN
    RAISE EXCEPTION 'field station: only letters A-Z, digits, space, dot, underscore and dash'
      USING ERRCODE = '22023';
  END IF;
  PERFORM public.palpa_check_session(p_session_id, p_trainee, p_case_title, p_case, p_started_at, p_mode,
                                     p_complete, p_samples, p_file_name, p_events, p_file);
  -- A station name belongs to the login that first pushed under it (or that a coordinator
  -- registered); the caller is known by session_user alone.
  INSERT INTO public.stations(name, db_user) VALUES (p_station, session_user) ON CONFLICT (name) DO NOTHING;
  SELECT st.db_user INTO v_owner FROM public.stations st WHERE st.name = p_station;
  IF v_owner IS DISTINCT FROM session_user THEN
    RAISE EXCEPTION 'station "%" is registered to another login', p_station USING ERRCODE = '42501';
  END IF;
  INSERT INTO public.trainees(name) VALUES (p_trainee) ON CONFLICT (name) DO NOTHING;
  SELECT t.id INTO v_trainee FROM public.trainees t WHERE t.name = p_trainee;
  v_case_sha := pg_catalog.encode(pg_catalog.sha256(pg_catalog.convert_to(p_case::text, 'UTF8')), 'hex');
  INSERT INTO public.cases(sha256, title, document) VALUES (v_case_sha, p_case_title, p_case)
    ON CONFLICT (sha256) DO NOTHING;
  SELECT c.id INTO v_case FROM public.cases c WHERE c.sha256 = v_case_sha;
  INSERT INTO public.sessions(session_id, station, trainee_id, case_id, started_at, mode, complete, samples,
                              size_bytes, sha256, file_name, events, file, uploaded_by)
    VALUES (p_session_id, p_station, v_trainee, v_case, p_started_at, p_mode, p_complete, p_samples,
            pg_catalog.octet_length(p_file), pg_catalog.encode(pg_catalog.sha256(p_file), 'hex'), p_file_name,
            p_events, p_file, session_user)
    ON CONFLICT (session_id) DO NOTHING
    RETURNING id INTO v_id;
  IF v_id IS NULL THEN  -- stored before (a second push, or at the same time from elsewhere)
    SELECT s.sha256, s.uploaded_by INTO v_sha, v_by FROM public.sessions s WHERE s.session_id = p_session_id;
    IF v_by IS DISTINCT FROM session_user THEN
      RAISE EXCEPTION 'session %: this id is taken; not stored', p_session_id USING ERRCODE = '23505';
    END IF;
    RETURN QUERY SELECT false, v_sha;
    RETURN;
  END IF;
  INSERT INTO public.work_queue(session_id) VALUES (v_id);
  RETURN QUERY SELECT true, s.sha256 FROM public.sessions s WHERE s.id = v_id;
END
$fn$;
ALTER FUNCTION public.palpa_push_session(text, text, text, text, jsonb, timestamptz, text, boolean, bigint, text,
                                         jsonb, bytea) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_push_session(text, text, text, text, jsonb, timestamptz, text, boolean, bigint,
                                                 text, jsonb, bytea) FROM PUBLIC;
GRANT EXECUTE ON FUNCTION public.palpa_push_session(text, text, text, text, jsonb, timestamptz, text, boolean,
                                                    bigint, text, jsonb, bytea) TO palpa_station;
GRANT SELECT ON public.store_settings TO palpa_worker, palpa_coordinator;
GRANT UPDATE ON public.store_settings TO palpa_coordinator;
GRANT INSERT, UPDATE (db_user) ON public.stations TO palpa_coordinator;
)sql";

}  // namespace

const std::vector<const char*>& migrations() {
  // Each version is one transaction made of parts, kept apart for reading.
  static const std::string v1 = std::string(kV1Tables) + kV1Push + kV1Roles;
  static const std::string v2 = std::string(kV2Owner) + kV2Checks + kV2Push;
  static const std::vector<const char*> kAll{v1.c_str(), v2.c_str(), migration_v3().c_str()};
  return kAll;
}

}  // namespace palpa::store
