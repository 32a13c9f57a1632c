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

}  // namespace

const std::vector<const char*>& migrations() {
  // Version 1 is one transaction made of three parts, kept apart for reading.
  static const std::string v1 = std::string(kV1Tables) + kV1Push + kV1Roles;
  static const std::vector<const char*> kAll{v1.c_str()};
  return kAll;
}

}  // namespace palpa::store
