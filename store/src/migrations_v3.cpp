// Schema version 3: the store under a hostile station, round two (docs/security.md,
// "The store's second round"). Constant SQL only, as every migration.
// - Work a station can cause is bounded: per-login quotas on pending sessions and bytes a
//   day, case and event documents whose text is bounded (no number whose text form is many
//   times its stored form), and waits for locks capped inside the functions a station calls.
// - The queue is fair: a worker claims from the login whose last claim is oldest.
// - Trainees are enrolled at stations: a push for a trainee from a station they are not
//   enrolled at is flagged (or refused, by setting), and start dates cannot run ahead of the
//   server's clock by more than a set skew.
// - Names are in NFKC, one script, without look-alike spacing.
#include "migrations.hpp"

namespace palpa::store {
namespace {

constexpr const char* kV3Tables = R"sql(
SET LOCAL lock_timeout = '60s';
ALTER TABLE public.store_settings
  ADD COLUMN max_pending_per_login integer NOT NULL DEFAULT 500 CHECK (max_pending_per_login BETWEEN 1 AND 10000000),
  ADD COLUMN max_bytes_per_login_day bigint NOT NULL DEFAULT 4294967296
    CHECK (max_bytes_per_login_day BETWEEN 65536 AND 1099511627776),
  ADD COLUMN max_start_skew_s integer NOT NULL DEFAULT 300 CHECK (max_start_skew_s BETWEEN 0 AND 86400),
  ADD COLUMN enrolment text NOT NULL DEFAULT 'flag' CHECK (enrolment IN ('flag', 'refuse'));
-- A session the day's quota could never take would wait in its outbox for ever.
ALTER TABLE public.store_settings ADD CONSTRAINT store_settings_day_holds_a_file
  CHECK (max_bytes_per_login_day >= max_file_bytes);
ALTER TABLE public.sessions ADD COLUMN enrolled boolean NOT NULL DEFAULT true;
-- What a push cost the store: the file, its events and, when it brought a new case, the
-- case document. The daily quota counts this, not the file alone.
ALTER TABLE public.sessions ADD COLUMN stored_bytes bigint;
UPDATE public.sessions SET stored_bytes = size_bytes + pg_catalog.pg_column_size(events);
ALTER TABLE public.sessions ALTER COLUMN stored_bytes SET NOT NULL;
ALTER TABLE public.cases DROP CONSTRAINT cases_sha256_key;
CREATE INDEX cases_sha256 ON public.cases(sha256);
CREATE INDEX sessions_login_day ON public.sessions(uploaded_by, uploaded_at) INCLUDE (stored_bytes);
ALTER TABLE public.work_queue ADD COLUMN login text;
UPDATE public.work_queue w SET login = s.uploaded_by FROM public.sessions s WHERE s.id = w.session_id;
ALTER TABLE public.work_queue ALTER COLUMN login SET NOT NULL;
CREATE INDEX work_queue_login_pending ON public.work_queue(login, session_id) WHERE NOT done;
-- When each login's session was last claimed: claims go to the login waiting longest.
CREATE TABLE public.claim_turns (
  login text PRIMARY KEY,
  last_claim timestamptz NOT NULL);
ALTER TABLE public.claim_turns OWNER TO palpa_owner;
-- Which stations may push for which trainee.
CREATE TABLE public.enrolments (
  trainee_id bigint NOT NULL REFERENCES public.trainees(id),
  station text NOT NULL REFERENCES public.stations(name),
  enrolled_by text NOT NULL DEFAULT session_user,
  enrolled_at timestamptz NOT NULL DEFAULT now(),
  PRIMARY KEY (trainee_id, station));
ALTER TABLE public.enrolments OWNER TO palpa_owner;
-- What was stored before keeps counting: each trainee is enrolled where they were pushed from.
INSERT INTO public.enrolments(trainee_id, station, enrolled_by)
  SELECT DISTINCT s.trainee_id, s.station, 'migration' FROM public.sessions s ON CONFLICT DO NOTHING;
-- Rows a version-2 store took with dates that are not finite are refused once, not retried.
UPDATE public.work_queue w SET done = true, lease_owner = NULL, lease_expires = NULL,
  last_error = 'refused: the start date is not a finite date'
  FROM public.sessions s WHERE s.id = w.session_id AND NOT w.done AND NOT pg_catalog.isfinite(s.started_at);
GRANT SELECT ON public.enrolments TO palpa_worker, palpa_coordinator;
GRANT SELECT ON public.claim_turns TO palpa_worker, palpa_coordinator;
)sql";

// Names a person reads: NFKC (no NBSP, no decomposed accents, no full-width letters), no
// space at either end or twice in a row, at most two combining marks on a letter, and
// letters of one script among Latin, the phonetic alphabet (IPA), Greek, Cyrillic,
// Armenian and Cherokee, the scripts whose letters look like Latin ones (no Cyrillic "а"
// inside "alice", no IPA "ɑ"). Look-alikes within one script (a dotless ı) remain: they
// are letters of real names. Checked when a name first enters the store: a trainee a
// version-2 store took keeps its name.
constexpr const char* kV3Names = R"sql(
-- The invisible characters of version 2, and the rest of Unicode's default-ignorable and
-- format characters a name could hide (as report/src/printable.cpp shows them).
CREATE OR REPLACE FUNCTION public.palpa_check_text(p_field text, p_value text, p_max integer)
  RETURNS void LANGUAGE plpgsql IMMUTABLE SET search_path = pg_catalog, pg_temp AS $fn$
BEGIN
  IF p_value IS NULL OR p_value = '' THEN
    RAISE EXCEPTION 'field %: empty', p_field USING ERRCODE = '22023';
  END IF;
  IF pg_catalog.char_length(p_value) > p_max THEN
    RAISE EXCEPTION 'field %: longer than % characters', p_field, p_max USING ERRCODE = '22023';
  END IF;
  IF p_value ~ ('[\u0001-\u001f\u007f-\u009f\u00ad\u034f\u061c\u115f\u1160\u17b4\u17b5\u180b-\u180f'
                '\u200b-\u200f\u2028-\u202e\u2060-\u206f\u3164\ufe00-\ufe0f\ufeff\uffa0\ufff0-\ufffb'
                '\u0600-\u0605\u06dd\u070f\u08e2\u2800\U000110bd\U000110cd\U00013430-\U0001343f'
                '\U0001bca0-\U0001bca3\U0001d173-\U0001d17a\U000e0000-\U000e0fff]') THEN
    RAISE EXCEPTION 'field %: holds a control, invisible or bidirectional-override character', p_field
      USING ERRCODE = '22023';
  END IF;
END
$fn$;

CREATE FUNCTION public.palpa_check_name(p_field text, p_value text, p_max integer)
  RETURNS void LANGUAGE plpgsql IMMUTABLE SET search_path = pg_catalog, pg_temp AS $fn$
DECLARE
  v_scripts integer;
BEGIN
  PERFORM public.palpa_check_text(p_field, p_value, p_max);
  IF NOT (p_value IS NFKC NORMALIZED) THEN
    RAISE EXCEPTION 'field %: not in Unicode normal form NFKC (a look-alike character or spacing)', p_field
      USING ERRCODE = '22023';
  END IF;
  IF p_value ~ '^\s|\s$|\s\s' THEN
    RAISE EXCEPTION 'field %: starts or ends with a space, or holds two in a row', p_field USING ERRCODE = '22023';
  END IF;
  IF p_value ~ ('[\u0300-\u036f\u0591-\u05c7\u0610-\u061a\u064b-\u065f\u0670\u06d6-\u06ed\u0900-\u0903'
                '\u093a-\u094f\u0e31\u0e34-\u0e3a\u0e47-\u0e4e\u1ab0-\u1aff\u1dc0-\u1dff\u20d0-\u20ff'
                '\ufe20-\ufe2f]{3}') THEN
    RAISE EXCEPTION 'field %: more than two combining marks on one letter', p_field USING ERRCODE = '22023';
  END IF;
  v_scripts := (p_value ~ '[A-Za-z\u00c0-\u024f\u1e00-\u1eff\u2c60-\u2c7f\ua720-\ua7ff]')::integer
               + (p_value ~ '[\u0250-\u02af\u1d00-\u1dbf]')::integer
               + (p_value ~ '[\u0370-\u03ff\u1f00-\u1fff]')::integer + (p_value ~ '[\u0400-\u052f\u1c80-\u1c8f\ua640-\ua69f]')::integer
               + (p_value ~ '[\u0530-\u058f]')::integer + (p_value ~ '[\u13a0-\u13ff\uab70-\uabbf]')::integer;
  -- Latin letters beside anything but Latin, digits, marks and punctuation (Coptic, Lisu,
  -- a click letter that looks like l): a mix.
  IF p_value ~ '[A-Za-z]' AND p_value ~ ('[^\u0020-\u007e\u00a0-\u01bf\u01c4-\u024f\u0300-\u036f\u1e00-\u1eff'
                                         '\u2010-\u2027\u2030-\u205e\u2c60-\u2c7f\ua720-\ua7ff]') THEN
    v_scripts := 2;
  END IF;
  IF v_scripts > 1 THEN
    RAISE EXCEPTION 'field %: mixes letters of Latin, IPA, Greek, Cyrillic, Armenian or Cherokee (look-alikes)', p_field
      USING ERRCODE = '22023';
  END IF;
END
$fn$;
ALTER FUNCTION public.palpa_check_name(text, text, integer) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_check_name(text, text, integer) FROM PUBLIC;

-- A JSON document whose text is bounded: every number below 1e15 in size with at most 40
-- digits after the point, so a number's text is at most about 60 characters whatever few
-- bytes it takes stored (1.0 followed by 16383 zeros takes 23), and the whole text at most
-- p_max bytes. Read number by number: nothing is made as text before it is known to be small.
CREATE FUNCTION public.palpa_document_amplified(p_value jsonb)
  RETURNS boolean LANGUAGE sql IMMUTABLE SET search_path = pg_catalog, pg_temp AS $fn$
  SELECT EXISTS (SELECT 1 FROM pg_catalog.jsonb_path_query(p_value, 'strict $.** ? (@.type() == "number")') AS n(v)
                 WHERE pg_catalog.scale(v::numeric) > 40 OR pg_catalog.abs(v::numeric) >= 1e15)
$fn$;
ALTER FUNCTION public.palpa_document_amplified(jsonb) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_document_amplified(jsonb) FROM PUBLIC;

CREATE FUNCTION public.palpa_check_document(p_field text, p_value jsonb, p_type text, p_max integer)
  RETURNS void LANGUAGE plpgsql IMMUTABLE SET search_path = pg_catalog, pg_temp AS $fn$
BEGIN
  IF p_value IS NULL OR pg_catalog.jsonb_typeof(p_value) <> p_type OR pg_catalog.pg_column_size(p_value) > p_max THEN
    RAISE EXCEPTION 'field %: not a JSON % of at most % bytes', p_field, p_type, p_max USING ERRCODE = '22023';
  END IF;
  IF public.palpa_document_amplified(p_value) THEN
    RAISE EXCEPTION 'field %: holds a number of 1e15 or more, or with more than 40 decimals', p_field
      USING ERRCODE = '22023';
  END IF;
  IF pg_catalog.octet_length(p_value::text) > p_max THEN
    RAISE EXCEPTION 'field %: longer than % bytes as text', p_field, p_max USING ERRCODE = '22023';
  END IF;
END
$fn$;
ALTER FUNCTION public.palpa_check_document(text, jsonb, text, integer) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_check_document(text, jsonb, text, integer) FROM PUBLIC;
)sql";

constexpr const char* kV3Checks = R"sql(
CREATE OR REPLACE FUNCTION public.palpa_check_session(p_session_id text, p_trainee text, p_case_title text,
    p_case jsonb, p_started_at timestamptz, p_mode text, p_complete boolean, p_samples bigint, p_file_name text,
    p_events jsonb, p_file bytea)
  RETURNS void LANGUAGE plpgsql STABLE SET search_path = pg_catalog, pg_temp AS $fn$
DECLARE
  v_settings public.store_settings;
BEGIN
  SELECT * INTO v_settings FROM public.store_settings;
  IF p_session_id IS NULL OR p_session_id !~ '^([0-9a-f]{32}|[0-9a-f]{16})$' THEN
    RAISE EXCEPTION 'field id: not a session id (32 lowercase hex digits)' USING ERRCODE = '22023';
  END IF;
  PERFORM public.palpa_check_text('trainee', p_trainee, 128);  -- a new one also palpa_check_name (the push)
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
     OR p_started_at > pg_catalog.now() + pg_catalog.make_interval(secs => v_settings.max_start_skew_s) THEN
    RAISE EXCEPTION 'field started_at: not between 2000-01-01 and the server''s clock plus % s '
                    '(store_settings.max_start_skew_s)', v_settings.max_start_skew_s USING ERRCODE = '22023';
  END IF;
  IF p_complete IS NOT TRUE THEN
    RAISE EXCEPTION 'field complete: the session has no end event' USING ERRCODE = '22023';
  END IF;
  IF p_samples IS NULL OR p_samples < 0 OR p_samples > 72000000 THEN
    RAISE EXCEPTION 'field samples: not between 0 and 72000000' USING ERRCODE = '22023';
  END IF;
  PERFORM public.palpa_check_document('case', p_case, 'object', 16777216);
  PERFORM public.palpa_check_document('events', p_events, 'array', 16777216);
  IF p_file IS NULL OR pg_catalog.octet_length(p_file) > v_settings.max_file_bytes THEN
    RAISE EXCEPTION 'field file: larger than the store accepts (% bytes; store_settings.max_file_bytes)',
      v_settings.max_file_bytes USING ERRCODE = '22023';
  END IF;
  IF pg_catalog.substr(p_file, 1, 16) <> '\x53514c69746520666f726d6174203300'::bytea THEN
    RAISE EXCEPTION 'field file: not an SQLite database (a Palpa session is one)' USING ERRCODE = '22023';
  END IF;
END
$fn$;

-- The login's quotas, checked with its stations' rows locked (two pushes of one login, under
-- any of its station names, cannot both pass the last free place). p_bytes: what this push
-- would store.
CREATE FUNCTION public.palpa_check_quota(p_bytes bigint)
  RETURNS void LANGUAGE plpgsql VOLATILE SET search_path = pg_catalog, pg_temp AS $fn$
DECLARE
  v_settings public.store_settings;
  v_pending bigint;
  v_bytes bigint;
BEGIN
  SELECT * INTO v_settings FROM public.store_settings;
  PERFORM 1 FROM public.stations st WHERE st.db_user = session_user FOR UPDATE;
  SELECT count(*) INTO v_pending FROM public.work_queue w WHERE w.login = session_user AND NOT w.done;
  IF v_pending >= v_settings.max_pending_per_login THEN
    RAISE EXCEPTION 'quota: this login has % sessions waiting to be scored (store_settings.max_pending_per_login); '
                    'try again once they are scored', v_pending USING ERRCODE = '53400';
  END IF;
  SELECT coalesce(sum(s.stored_bytes), 0) INTO v_bytes FROM public.sessions s
    WHERE s.uploaded_by = session_user AND s.uploaded_at > pg_catalog.now() - interval '1 day';
  IF v_bytes + p_bytes > v_settings.max_bytes_per_login_day THEN
    RAISE EXCEPTION 'quota: this login pushed % bytes in the last 24 hours (store_settings.max_bytes_per_login_day)',
      v_bytes USING ERRCODE = '53400';
  END IF;
END
$fn$;
ALTER FUNCTION public.palpa_check_quota(bigint) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_check_quota(bigint) FROM PUBLIC;
)sql";

// The push, with its waits capped: a lock another login holds (an open transaction that
// inserted the same new trainee) ends this push after 5 s with a retryable error (55P03)
// instead of holding it for as long as that login wishes. SET on a function cannot be
// lifted by the caller: it applies inside the call whatever the session set. (A
// statement_timeout set there would not: its clock starts with the caller's statement.)
constexpr const char* kV3Push = R"sql(
-- The checksum of the session stored under this id by the caller's login, or NULL when
-- none is; an id another login took is refused without saying whose it is.
CREATE FUNCTION public.palpa_stored_sha(p_session_id text)
  RETURNS text LANGUAGE plpgsql STABLE SET search_path = pg_catalog, pg_temp AS $fn$
DECLARE
  v_sha text;
  v_by text;
BEGIN
  SELECT s.sha256, s.uploaded_by INTO v_sha, v_by FROM public.sessions s WHERE s.session_id = p_session_id;
  IF FOUND AND v_by IS DISTINCT FROM session_user THEN
    RAISE EXCEPTION 'session %: this id is taken; not stored', p_session_id USING ERRCODE = '23505';
  END IF;
  RETURN v_sha;
END
$fn$;
ALTER FUNCTION public.palpa_stored_sha(text) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_stored_sha(text) FROM PUBLIC;

CREATE OR REPLACE FUNCTION public.palpa_push_session(p_station text, p_session_id text, p_trainee text,
    p_case_title text, p_case jsonb, p_started_at timestamptz, p_mode text, p_complete boolean, p_samples bigint,
    p_file_name text, p_events jsonb, p_file bytea)
  RETURNS TABLE (stored boolean, server_sha256 text)
  LANGUAGE plpgsql SECURITY DEFINER SET search_path = pg_catalog, public, pg_temp SET lock_timeout = '5s' AS $fn$
DECLARE
  v_owner text;
  v_sha text;
  v_case_sha text;
  v_trainee bigint;
  v_new_trainee boolean := false;
  v_enrolled boolean;
  v_case bigint;
  v_id bigint;
  v_bytes bigint;
BEGIN
  PERFORM public.palpa_check_text('station', p_station, 64);
  IF p_station !~ '^[A-Za-z0-9][A-Za-z0-9 ._-]*$' OR p_station ~ '\s$|\s\s' THEN
    RAISE EXCEPTION 'field station: only letters A-Z, digits, single spaces, dot, underscore and dash'
      USING ERRCODE = '22023';
  END IF;
  PERFORM public.palpa_check_session(p_session_id, p_trainee, p_case_title, p_case, p_started_at, p_mode,
                                     p_complete, p_samples, p_file_name, p_events, p_file);
  INSERT INTO public.stations(name, db_user) VALUES (p_station, session_user) ON CONFLICT (name) DO NOTHING;
  SELECT st.db_user INTO v_owner FROM public.stations st WHERE st.name = p_station;
  IF v_owner IS DISTINCT FROM session_user THEN
    RAISE EXCEPTION 'station "%" is registered to another login', p_station USING ERRCODE = '42501';
  END IF;
  v_sha := public.palpa_stored_sha(p_session_id);
  IF v_sha IS NOT NULL THEN
    RETURN QUERY SELECT false, v_sha;
    RETURN;
  END IF;
  v_case_sha := pg_catalog.encode(pg_catalog.sha256(pg_catalog.convert_to(p_case::text, 'UTF8')), 'hex');
  SELECT c.id INTO v_case FROM public.cases c WHERE c.sha256 = v_case_sha ORDER BY c.id LIMIT 1;
  v_bytes := pg_catalog.octet_length(p_file) + pg_catalog.pg_column_size(p_events)
             + CASE WHEN v_case IS NULL THEN pg_catalog.pg_column_size(p_case) ELSE 0 END;
  PERFORM public.palpa_check_quota(v_bytes);
  SELECT t.id INTO v_trainee FROM public.trainees t WHERE t.name = p_trainee;
  IF v_trainee IS NULL THEN PERFORM public.palpa_check_name('trainee', p_trainee, 128); END IF;
  IF v_trainee IS NULL AND (SELECT st.enrolment FROM public.store_settings st) = 'flag' THEN
    INSERT INTO public.trainees(name) VALUES (p_trainee) ON CONFLICT (name) DO NOTHING RETURNING id INTO v_trainee;
    v_new_trainee := v_trainee IS NOT NULL;
    IF NOT v_new_trainee THEN SELECT t.id INTO v_trainee FROM public.trainees t WHERE t.name = p_trainee; END IF;
  END IF;
  IF v_new_trainee THEN  -- a new trainee belongs to the station that first pushed for them
    INSERT INTO public.enrolments(trainee_id, station, enrolled_by) VALUES (v_trainee, p_station, 'first push');
  END IF;
  v_enrolled := v_trainee IS NOT NULL AND EXISTS (SELECT 1 FROM public.enrolments e
                                                  WHERE e.trainee_id = v_trainee AND e.station = p_station);
  IF NOT v_enrolled AND (SELECT st.enrolment FROM public.store_settings st) = 'refuse' THEN
    -- The same words whether the trainee exists or not: no list of names to probe.
    RAISE EXCEPTION 'field trainee: not enrolled at station "%" (a coordinator enrols: palpa-cli store enrol)',
      p_station USING ERRCODE = '42501';
  END IF;
  -- No unique key to wait on: a station holding a new case's row in an open transaction
  -- would hold every push of that case. Two pushes of a new case at once make two rows.
  IF v_case IS NULL THEN
    INSERT INTO public.cases(sha256, title, document) VALUES (v_case_sha, p_case_title, p_case) RETURNING id INTO v_case;
  END IF;
  INSERT INTO public.sessions(session_id, station, trainee_id, case_id, started_at, mode, complete, samples,
                              size_bytes, sha256, file_name, events, file, uploaded_by, enrolled, stored_bytes)
    VALUES (p_session_id, p_station, v_trainee, v_case, p_started_at, p_mode, p_complete, p_samples,
            pg_catalog.octet_length(p_file), pg_catalog.encode(pg_catalog.sha256(p_file), 'hex'), p_file_name,
            p_events, p_file, session_user, v_enrolled, v_bytes)
    ON CONFLICT (session_id) DO NOTHING
    RETURNING id INTO v_id;
  IF v_id IS NULL THEN  -- the same id pushed at the same time from elsewhere
    RETURN QUERY SELECT false, public.palpa_stored_sha(p_session_id);
    RETURN;
  END IF;
  INSERT INTO public.work_queue(session_id, login) VALUES (v_id, session_user);
  RETURN QUERY SELECT true, s.sha256 FROM public.sessions s WHERE s.id = v_id;
END
$fn$;
)sql";

// A worker's claim: the free session of the login whose last claim is oldest (round robin
// over logins; a login never claimed comes first), the lowest id within it.
constexpr const char* kV3Claim = R"sql(
CREATE FUNCTION public.palpa_claim_session(p_owner text, p_lease_s double precision)
  RETURNS bigint LANGUAGE plpgsql SECURITY DEFINER SET search_path = pg_catalog, public, pg_temp
  SET lock_timeout = '5s' AS $fn$
DECLARE
  v_login text;
  v_id bigint;
BEGIN
  FOR v_login IN
    SELECT f.login FROM (SELECT DISTINCT q.login FROM public.work_queue q
                         WHERE NOT q.done AND q.attempts < (SELECT st.max_score_attempts FROM public.store_settings st)
                           AND (q.lease_expires IS NULL OR q.lease_expires < pg_catalog.now()
                                OR q.lease_owner = p_owner)) f
      LEFT JOIN public.claim_turns ct ON ct.login = f.login
      ORDER BY ct.last_claim NULLS FIRST, f.login
  LOOP
    SELECT q.session_id INTO v_id FROM public.work_queue q
      WHERE q.login = v_login AND NOT q.done
        AND q.attempts < (SELECT st.max_score_attempts FROM public.store_settings st)
        AND (q.lease_expires IS NULL OR q.lease_expires < pg_catalog.now() OR q.lease_owner = p_owner)
      ORDER BY q.session_id LIMIT 1 FOR UPDATE SKIP LOCKED;
    IF v_id IS NOT NULL THEN
      UPDATE public.work_queue w SET lease_owner = p_owner,
        lease_expires = pg_catalog.now() + pg_catalog.make_interval(secs => p_lease_s), attempts = w.attempts + 1
        WHERE w.session_id = v_id;
      INSERT INTO public.claim_turns(login, last_claim) VALUES (v_login, pg_catalog.clock_timestamp())
        ON CONFLICT (login) DO UPDATE SET last_claim = excluded.last_claim;
      RETURN v_id;
    END IF;
  END LOOP;
  RETURN NULL;
END
$fn$;
ALTER FUNCTION public.palpa_claim_session(text, double precision) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_claim_session(text, double precision) FROM PUBLIC;
GRANT EXECUTE ON FUNCTION public.palpa_claim_session(text, double precision) TO palpa_worker;
-- Documents a version-2 store took whose text is far larger than stored are never made
-- into text by a worker: their sessions are ended once, with the reason.
UPDATE public.work_queue w SET done = true, lease_owner = NULL, lease_expires = NULL,
  last_error = 'refused: its case or events hold a number whose text is far larger than stored'
  FROM public.sessions s JOIN public.cases c ON c.id = s.case_id
  WHERE s.id = w.session_id AND NOT w.done
    AND (public.palpa_document_amplified(c.document) OR public.palpa_document_amplified(s.events));
)sql";

// A coordinator's enrolment: trainee (made if new) at a station that exists; p_enrol false
// ends it. Returns whether anything changed.
constexpr const char* kV3Enrol = R"sql(
CREATE FUNCTION public.palpa_enrol(p_trainee text, p_station text, p_enrol boolean)
  RETURNS boolean LANGUAGE plpgsql SECURITY DEFINER SET search_path = pg_catalog, public, pg_temp
  SET lock_timeout = '5s' AS $fn$
DECLARE
  v_trainee bigint;
  v_rows integer;
BEGIN
  IF NOT EXISTS (SELECT 1 FROM public.trainees t WHERE t.name = p_trainee) THEN
    PERFORM public.palpa_check_name('trainee', p_trainee, 128);
  END IF;
  IF NOT EXISTS (SELECT 1 FROM public.stations st WHERE st.name = p_station) THEN
    RAISE EXCEPTION 'field station: no station "%" has pushed or been registered', p_station USING ERRCODE = '22023';
  END IF;
  INSERT INTO public.trainees(name) VALUES (p_trainee) ON CONFLICT (name) DO NOTHING;
  SELECT t.id INTO v_trainee FROM public.trainees t WHERE t.name = p_trainee;
  IF p_enrol THEN
    -- A coordinator's word replaces a first push's: the enrolment is confirmed.
    INSERT INTO public.enrolments(trainee_id, station) VALUES (v_trainee, p_station)
      ON CONFLICT (trainee_id, station) DO UPDATE SET enrolled_by = session_user, enrolled_at = pg_catalog.now()
      WHERE public.enrolments.enrolled_by = 'first push';
  ELSE
    DELETE FROM public.enrolments e WHERE e.trainee_id = v_trainee AND e.station = p_station;
  END IF;
  GET DIAGNOSTICS v_rows = ROW_COUNT;
  RETURN v_rows > 0;
END
$fn$;
ALTER FUNCTION public.palpa_enrol(text, text, boolean) OWNER TO palpa_owner;
REVOKE ALL ON FUNCTION public.palpa_enrol(text, text, boolean) FROM PUBLIC;
GRANT EXECUTE ON FUNCTION public.palpa_enrol(text, text, boolean) TO palpa_coordinator;
)sql";

}  // namespace

const std::string& migration_v3() {
  static const std::string v3 = std::string(kV3Tables) + kV3Names + kV3Checks + kV3Push + kV3Claim + kV3Enrol;
  return v3;
}

}  // namespace palpa::store
