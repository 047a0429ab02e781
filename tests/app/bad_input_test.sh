#!/usr/bin/env bash
# Bad input across scene files, campaign files, the results database and the command line:
# each row of docs/errors.md, by its id. Every case must exit with code 2, print a message on
# stderr that names the file (or option), the key and what is accepted, and write nothing:
# no output folder, no database file, every existing file (databases included) unchanged.
# Usage: bad_input_test.sh FIBRENET DATA_DIR
set -euo pipefail
fibrenet=$(realpath "$1")
data=$(realpath "$2")
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
logs=$work/logs
mkdir -p "$logs" "$work/files"
cd "$work/files"
fail() { echo "FAIL: $*" >&2; exit 1; }
cp "$data/scene.toml" "$data/campaign.toml" "$data/scene_campaign.toml" .

# A valid database to query and to leave unchanged.
"$fibrenet" campaign run campaign.toml --db good.db --quiet > /dev/null
count() {
  python3 -c "import sqlite3, sys
db = sqlite3.connect('file:' + sys.argv[1] + '?immutable=1', uri=True)
print(db.execute('select count(*) from candidates').fetchone()[0])" "$1"
}
candidates=$(count good.db)
[ "$candidates" -gt 4 ] || fail "the valid campaign stored only $candidates candidates"

# Everything under files/: names, modes, and the sizes and modification times of files (a new
# file or folder, or any write, shows), plus the checksums of the databases. Reading a WAL
# database read-only (db commands) leaves its shared-memory index and an empty WAL next to
# it, as every SQLite reader does; a WAL that holds pages does count. A folder's time changes
# when SQLite makes and removes its journal, which writes nothing.
# One find, unsorted (the order of an unchanged folder is stable): it runs twice per case.
state() {
  find . \( ! -name '*-shm' ! \( -name '*-wal' -empty \) \
    \( -type d -printf '%p %m\n' -o -printf '%p %s %T@ %m\n' \) \) \
    , \( -name '*.db' -type f -readable -exec md5sum {} + \)
}

# variant NEW FROM SED_SCRIPT: a copy of FROM with one edit, which must change it.
variant() {
  sed "$3" "$2" > "$1"
  ! cmp -s "$1" "$2" || fail "variant $1: the edit '$3' matched nothing in $2"
}

# bad ID WANT... -- COMMAND...: exit code 2, every WANT (fixed text) on stderr, nothing on
# stdout, nothing written.
bad() {
  local id=$1 wants=()
  shift
  while [ "$1" != -- ]; do wants+=("$1"); shift; done
  shift
  local before
  before=$(state)
  set +e
  "$@" > "$logs/$id.out" 2> "$logs/$id.err"
  local rc=$?
  set -e
  [ $rc = 2 ] || { cat "$logs/$id.err"; fail "$id: exit code $rc, expected 2: $*"; }
  local want
  for want in "${wants[@]}"; do
    grep -qF -- "$want" "$logs/$id.err" || { cat "$logs/$id.err"; fail "$id: message lacks '$want'"; }
  done
  [ ! -s "$logs/$id.out" ] || fail "$id: printed on stdout: $(head -c 200 "$logs/$id.out")"
  [ "$(state)" = "$before" ] || { diff <(echo "$before") <(state) || true; fail "$id: wrote files"; }
  echo "ok $id: $(head -n 1 "$logs/$id.err")"
}
run() { "$fibrenet" run "$@" --out out; }                 # out/ must never appear
campaign() { "$fibrenet" campaign run "$@"; }

# --- scene files: fibrenet run SCENE --out out ---------------------------------------------
variant s01.toml scene.toml 's/^length_mm = 0.4/lenght_mm = 0.4/'
bad s01 "s01.toml: unknown key 'fibres.lenght_mm'; did you mean 'fibres.length_mm'?" \
  "accepted in [fibres]: bend_angle_deg, coarseness_mg_per_100m, diameter_um," -- run s01.toml
variant s02.toml scene.toml 's/^length_mm = 0.4/length_mm = "long"/'
bad s02 "s02.toml: fibres.length_mm: expected a number or a distribution table, got a string" \
  -- run s02.toml
variant s03.toml scene.toml 's/^length_mm = 0.4/length_mm = -0.4/'
bad s03 "s03.toml: fibres.length_mm: -0.4 is out of range; accepted (0, 100] mm" -- run s03.toml
variant s04.toml scene.toml 's/^size_x_mm = 0.6/size_x_mm = 0/'
bad s04 "s04.toml: cell.size_x_mm: 0 is out of range; accepted (0, 1000] mm" -- run s04.toml
variant s05.toml scene.toml '$a [contact]\nlinear_below = 1.5'
bad s05 "s05.toml: contact.linear_below: 1.5 is out of range; accepted (0, 1) of R_i + R_j" \
  -- run s05.toml
variant s06.toml scene.toml 's/^consistency_percent = 1.0/consistency_percent = 150/'
bad s06 "s06.toml: forming.consistency_percent: 150 is out of range; accepted (0, 100) %" \
  -- run s06.toml
variant s07.toml scene.toml 's/^length_mm = 0.4/length_mm = nan/'
bad s07 "s07.toml: fibres.length_mm: nan is out of range; accepted (0, 100] mm" -- run s07.toml
variant s08.toml scene.toml 's/^basis_weight_gsm = 20/basis_weight_gsm = inf/'
bad s08 "s08.toml: cell.basis_weight_gsm: inf is out of range; accepted (0, 1000] g/m^2" \
  -- run s08.toml
variant s09.toml scene.toml 's/^segments = 4/segments = 2.5/'
bad s09 "s09.toml: fibres.segments: expected an integer in [1, 1000], got a number" -- run s09.toml
variant s10.toml scene.toml 's/min = 16, max = 35/min = 35, max = 16/'
bad s10 "s10.toml: fibres.coarseness_mg_per_100m.max: must be >= min = 35" -- run s10.toml
variant s11.toml scene.toml 's/^consistency_percent = 1.0/&\norientation = "planer"/'
bad s11 "s11.toml: forming.orientation: \"planer\" is not accepted; accepted: \"isotropic\", \"planar\"" \
  "did you mean \"planar\"?" -- run s11.toml
variant s12.toml scene.toml 's/^length_mm = 0.4/length_mm = 0.7/'
bad s12 "s12.toml: fibres.length_mm: the mean fibre length 0.7 mm must be shorter than the cell side 0.6 mm" \
  -- run s12.toml
variant s13.toml scene.toml 's/^target_thickness_um = 150/&\ntarget_pressure_kPa = 10/'
bad s13 "s13.toml: pressing.target_pressure_kPa: give target_thickness_um or target_pressure_kPa, not both" \
  -- run s13.toml
variant s14.toml scene.toml 's/^size_\([xy]\)_mm = 0.6/size_\1_mm = 1000/; s/^basis_weight_gsm = 20/basis_weight_gsm = 1000/'
bad s14 "s14.toml: cell: the scene would make about" "particles" "of memory; accepted: at most about" \
  -- run s14.toml
bad s15 "missing.toml: cannot open the scene file (missing or unreadable)" -- run missing.toml
: > s16.toml
bad s16 "s16.toml: the file is empty; accepted: a scene with at least a [forming] table" -- run s16.toml
variant s17.toml scene.toml 's/^\[pressing\]$/[pressing/'
bad s17 "s17.toml:32:10: TOML syntax error" -- run s17.toml
mkdir s18.toml
bad s18 "s18.toml: is a folder; accepted: a scene file (TOML)" -- run s18.toml
variant s19.toml scene.toml '$a [creping]\ncreping_angle_deg = 170'
bad s19 "s19.toml: creping.creping_angle_deg: 170 is out of range; accepted [30, 150] deg" \
  -- run s19.toml
sed '/^\[pressing/,$d' scene.toml > s20.toml
printf '[creping]\nyankee_speed_m_per_s = 30\n' >> s20.toml
bad s20 "s20.toml: creping: the sheet is creped after consolidation: add [pressing] or [through_air]" \
  -- run s20.toml
# A file name longer than the system's limit (255 bytes): the system's reason, not a crash.
long=$(printf 'n%.0s' {1..300})
bad s21 "$long.toml: cannot open the scene file (File name too long)" -- run "$long.toml"

# --- the run command line -------------------------------------------------------------------
bad r01 "scene.toml: unknown key 'fibres.lenght_mm' (override); did you mean 'fibres.length_mm'?" \
  -- run scene.toml --set fibres.lenght_mm=0.5
bad r02 "override 'fibres.length_mm=abc': 'abc' is not a number; accepted: KEY=NUMBER" \
  -- run scene.toml --set fibres.length_mm=abc
bad r03 "override 'fibres.length_mm': no '='; accepted: KEY=NUMBER" \
  -- run scene.toml --set fibres.length_mm
bad r04 "scene.toml: override 'fibres.length_mm': nan is not accepted; accepted: a finite number" \
  -- run scene.toml --set fibres.length_mm=nan
bad r05 "scene.toml: contact.linear_below (override): 1.5 is out of range; accepted (0, 1)" \
  -- run scene.toml --set contact.linear_below=1.5
bad r06 "scene.toml: override 'tensile.strain_rate_per_s': the scene has no [tensile] table: an override cannot enable a stage" \
  -- run scene.toml --set tensile.strain_rate_per_s=1
bad r07 "scene.toml: seed (override): expected an integer in [0, 9223372036854775807], got a number" \
  -- run scene.toml --set seed=1.5
bad r08 "--threads: Value 0 not in range 1 to 1024" -- run scene.toml --threads 0
bad r09 "--threads: Value abc not in range 1 to 1024" -- run scene.toml --threads abc
bad r10 "--out: '$PWD/scene.toml' is not a folder; accepted: a folder, existing or new" \
  -- "$fibrenet" run scene.toml --out scene.toml
bad r11 "--out: '$PWD/scene.toml' is not a folder, so scene.toml/out cannot be made" \
  -- "$fibrenet" run scene.toml --out scene.toml/out
bad r12 "The following argument was not expected: --frobnicate" -- run scene.toml --frobnicate

# --- campaign files: fibrenet campaign run CAMPAIGN --db new.db (new.db must never appear) --
variant k01.toml campaign.toml 's/^max_evaluations = 6/max_evals = 6/'
bad k01 "k01.toml:36: budget.max_evals: unknown key; did you mean 'max_evaluations'?" \
  -- campaign k01.toml --db new.db
variant k02.toml campaign.toml 's/^seed = 2/seed = "two"/'
bad k02 "k02.toml:6: seed: must be an integer; got a string" -- campaign k02.toml --db new.db
variant k03.toml campaign.toml 's/^upper = 3.0/upper = -3.0/'
bad k03 "k03.toml:8: variables[0]: variable 'a': bounds must be finite with lower < upper; got [-2, -3]" \
  -- campaign k03.toml --db new.db
variant k04.toml campaign.toml 's/^upper = 3.0/upper = nan/'
bad k04 "k04.toml:8: variables[0]: variable 'a': bounds must be finite with lower < upper; got [-2, nan]" \
  -- campaign k04.toml --db new.db
variant k05.toml campaign.toml 's/^lower = -2.0/lower = -inf/'
bad k05 "k05.toml:8: variables[0]: variable 'a': bounds must be finite with lower < upper; got [-inf, 3]" \
  -- campaign k05.toml --db new.db
variant k06.toml campaign.toml 's/^upper = 3.0/&\nlog = true/'
bad k06 "k06.toml:8: variables[0]: variable 'a': log scale needs lower > 0" -- campaign k06.toml --db new.db
variant k07.toml scene_campaign.toml 's/^key = "fibres.diameter_um"/key = "fibres.diametre_um"/'
bad k07 "k07.toml:14: variables[1].key: 'fibres.diametre_um' is refused by the base scene (at lower = 25 and upper = 40)" \
  "scene.toml: unknown key 'fibres.diametre_um' (override); did you mean 'fibres.diameter_um'?" \
  -- campaign k07.toml --db new.db
variant k08.toml scene_campaign.toml 's/^upper = 40/upper = 2000/'
bad k08 "k08.toml:16: variables[1].upper: fibres.diameter_um = 2000 is refused by the base scene" \
  "fibres.diameter_um (override): 2000 is out of range; accepted (0, 1000] um" \
  -- campaign k08.toml --db new.db
variant k09.toml scene_campaign.toml 's/^"fidelity.particle_spacing_diameters" = 2/"fibres.particles_per_fibre" = 6/'
bad k09 "k09.toml:21: fidelity[0].overrides: refused by the base scene" \
  "scene.toml: unknown key 'fibres.particles_per_fibre' (override); accepted in [fibres]: bend_angle_deg," \
  -- campaign k09.toml --db new.db
variant k10.toml campaign.toml 's/"analytic.noise"/"analytic.noize"/'
bad k10 "k10.toml:25: fidelity[0].overrides: fidelity 'exact': override 'analytic.noize' is not a key of the analytic test functions; did you mean 'analytic.noise'?" \
  -- campaign k10.toml --db new.db
variant k11.toml campaign.toml 's/^minimise = "quadratic"/minimise = "quadratik"/'
bad k11 "k11.toml:20: goals.minimise: metric 'quadratik' is not produced by analytic:quadratic; did you mean 'quadratic'?; accepted: noisy_quadratic, product, quadratic, sum" \
  -- campaign k11.toml --db new.db
variant k12.toml campaign.toml 's/^sum = { max = 2.5 }/summ = { max = 2.5 }/'
bad k12 "k12.toml:23: goals.constraints.summ: metric 'summ' is not produced by analytic:quadratic; did you mean 'sum'?" \
  -- campaign k12.toml --db new.db
variant k13.toml campaign.toml 's/LN_NELDERMEAD/LN_NELDERMAED/'
bad k13 "k13.toml:33: algorithm.name: unknown algorithm 'LN_NELDERMAED'; did you mean 'LN_NELDERMEAD'?; accepted: LN_COBYLA," \
  -- campaign k13.toml --db new.db
bad k14 "missing.toml: cannot read campaign file (no such file)" -- campaign missing.toml --db new.db
variant k15.toml campaign.toml 's|analytic:quadratic|scenes/none.toml|'
bad k15 "k15.toml:5: base_scene: scene file '$PWD/scenes/none.toml' does not exist" \
  -- campaign k15.toml --db new.db
variant k16.toml scene_campaign.toml 's|^base_scene = "scene.toml"|base_scene = "s01.toml"|'
bad k16 "k16.toml:5: base_scene: $PWD/s01.toml: unknown key 'fibres.lenght_mm'; did you mean 'fibres.length_mm'?" \
  -- campaign k16.toml --db new.db
: > k17.toml
bad k17 "k17.toml: the file is empty; accepted: a campaign with base_scene, [[variables]], [goals]" \
  -- campaign k17.toml --db new.db
variant k18.toml campaign.toml 's/^\[doe\]/[doe/'
bad k18 "k18.toml:29: TOML syntax error" -- campaign k18.toml --db new.db
variant k19.toml campaign.toml 's/^points = 4/points = 0/'
bad k19 "k19.toml:30: doe.points: must be an integer >= 1; got 0" -- campaign k19.toml --db new.db
variant k20.toml campaign.toml 's/^name = "LN_NELDERMEAD"/&\ninitial_step = 2/'
bad k20 "k20.toml:34: algorithm.initial_step: must lie in (0, 1]" -- campaign k20.toml --db new.db
cat > k21.toml <<'TOML'
base_scene = "analytic:softstrong"
[[variables]]
key = "a"
lower = 0.0
upper = 1.0
[goals]
minimise = "basis_weight"
[doe]
points = 2
TOML
bad k21 "k21.toml:1: base_scene: analytic:softstrong needs at least two design variables" \
  -- campaign k21.toml --db new.db
variant k22.toml campaign.toml 's/^sum = { max = 2.5 }/sum = { min = 3, max = 2.5 }/'
bad k22 "k22.toml:19: goals: constraint 'sum': min (3) must not exceed max (2.5)" -- campaign k22.toml --db new.db
variant k23.toml campaign.toml '/^\[algorithm\]/,/^name/d; /^\[doe\]/,/^points/d'
bad k23 "k23.toml:1: a campaign needs an [algorithm] table, a [doe] table, or both" \
  -- campaign k23.toml --db new.db
variant k24.toml campaign.toml 's/^sum = { max = 2.5 }/sum = { max = 2.4 }/'
bad k24 "k24.toml: campaign 'quick' in database good.db was started from a different campaign file" \
  -- campaign k24.toml --db good.db
variant k25.toml campaign.toml 's/^points = 4/points = 2147483647/'
bad k25 "k25.toml:30: doe.points: must be an integer <= 1000000; got 2147483647" \
  -- campaign k25.toml --db new.db
variant k26.toml scene_campaign.toml "s/^base_scene = .*/base_scene = \"$long.toml\"/"
bad k26 "k26.toml:5: base_scene: scene file '$PWD/$long.toml' cannot be read: File name too long" \
  -- campaign k26.toml --db new.db

# --- the results database -------------------------------------------------------------------
bad d01 "results database 'nofolder/new.db': cannot open: folder 'nofolder' does not exist; accepted: a file in an existing folder" \
  -- campaign scene_campaign.toml --db nofolder/new.db
mkdir folder.db
bad d02 "results database 'folder.db': cannot open: it is a folder; accepted: the path of a database file" \
  -- campaign campaign.toml --db folder.db
bad d03 "results database 'scene.toml/new.db': cannot open: 'scene.toml' is not a folder; accepted: a file in an existing folder" \
  -- campaign campaign.toml --db scene.toml/new.db
# d04, d18, d19: permissions. Root reads and writes anywhere, so as root (as in CI) fibrenet
# runs as nobody here (setpriv, else runuser), and files/ and the folder or file of each row
# belong to nobody: as for any other user, only the mode of that folder or file stands in the
# way. Where nobody cannot run fibrenet in files/, the rows are skipped, and the test says so.
as_user() { "$@"; }
own() { :; }
permissions=yes
if [ "$(id -u)" = 0 ]; then
  uid=$(id -u nobody 2> /dev/null) && gid=$(id -g nobody) || uid=
  if [ -z "$uid" ]; then
    permissions="there is no user nobody"
  elif command -v setpriv > /dev/null; then
    as_user() { setpriv --reuid="$uid" --regid="$gid" --clear-groups -- "$@"; }
  elif command -v runuser > /dev/null; then
    as_user() { runuser -u nobody -- "$@"; }
  else
    permissions="neither setpriv nor runuser (util-linux) is installed"
  fi
  if [ "$permissions" = yes ]; then
    own() { chown "$uid:$gid" "$@"; }
    chmod o+x "$work" && own .
    as_user test -w . -a -r campaign.toml -a -x "$fibrenet" \
      && as_user "$fibrenet" --version > /dev/null 2>&1 \
      || permissions="user nobody (uid $uid) cannot run $fibrenet in $PWD: check the modes of its folders"
  fi
fi
if [ "$permissions" = yes ]; then
  mkdir readonly && own readonly && chmod 555 readonly
  bad d04 "results database 'readonly/new.db': cannot open: folder 'readonly' is not writable" \
    -- as_user "$fibrenet" campaign run campaign.toml --db readonly/new.db
  cp good.db locked.db && own locked.db && chmod 000 locked.db
  bad d18 "results database 'locked.db': cannot open: the file is not readable" \
    -- as_user "$fibrenet" db list --db locked.db
  cp good.db readonly.db && own readonly.db && chmod 444 readonly.db
  bad d19 "results database 'readonly.db': cannot open: the file is not writable" \
    -- as_user "$fibrenet" campaign run campaign.toml --db readonly.db
else
  echo "skip d04, d18, d19: running as root, which reads and writes without permission, and $permissions"
fi
cp good.db v99.db
python3 -c "import sqlite3; sqlite3.connect('v99.db').execute('pragma user_version = 99')"
bad d05 "results database 'v99.db': unknown schema version 99: this build of fibrenet reads schema versions 1 to 1" \
  -- campaign campaign.toml --db v99.db
bad d06 "results database 'v99.db': unknown schema version 99" -- "$fibrenet" db list --db v99.db
echo "not a database" > text.db
bad d07 "results database 'text.db': not an SQLite database" -- campaign campaign.toml --db text.db
python3 -c "import sqlite3; c = sqlite3.connect('other.db'); c.execute('create table t (x)'); c.commit()"
bad d08 "results database 'other.db': not a fibrenet results database: it is an SQLite file of another application" \
  -- campaign campaign.toml --db other.db
bad d09 "results database 'none.db': cannot open: no such file; accepted: an existing results database" \
  -- "$fibrenet" db list --db none.db
: > empty.db
bad d10 "results database 'empty.db': not a fibrenet results database: the file is empty" \
  -- "$fibrenet" db list --db empty.db
bad d11 "--db good.db: no candidate with id 9999; accepted: the id of a stored candidate" \
  -- "$fibrenet" db show 9999 --db good.db
bad d12 "candidate: 'abc' is not accepted; accepted: a candidate id, an integer >= 1" \
  -- "$fibrenet" db show abc --db good.db
bad d13 "--campaign 'quik': no such campaign in good.db; did you mean 'quick'?; accepted: quick" \
  -- "$fibrenet" db best --db good.db --campaign quik
bad d14 "--campaign 'nope': no such campaign in good.db; accepted: quick" \
  -- "$fibrenet" db export --db good.db --campaign nope --format csv
bad d15 "--format 'xml': accepted: csv, json" \
  -- "$fibrenet" db export --db good.db --campaign quick --format xml
bad d16 "--out nofolder/quick.csv: cannot write the file; accepted: a file in an existing, writable folder" \
  -- "$fibrenet" db export --db good.db --campaign quick --out nofolder/quick.csv
bad d17 "-n: 'abc' is not accepted; accepted: an integer (negative: all)" \
  -- "$fibrenet" db best --db good.db --campaign quick -n abc
bad d20 "results database '$long.db': cannot open: File name too long; accepted: the path of a database file" \
  -- campaign campaign.toml --db "$long.db"

[ "$(count good.db)" = "$candidates" ] || fail "good.db changed: $(count good.db) candidates"
echo "bad input test passed"
