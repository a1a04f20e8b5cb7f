# Curve squeal pipeline: geometry -> wheel modes -> ... (see README).
# `make` sets up the machine and runs the default case as far as the stages
# exist; `make test` sets up and runs the test suite.  Select inputs with
# CASE=<name> (pipeline/cases/; the case names its wheel and rail), WHEEL=<name>
# (geometry/wheels/) and RAIL=<name> (geometry/rails/) for the wheel and rail
# stages alone, STUDY=<name> (pipeline/studies/).

CASE  ?= default
BUILD ?= build
PY    := .venv/bin/python
STAMP := .venv/.setup-stamp
# the venv in three steps, each installed when a goal first needs it: the computing stages' packages
# (requirements-core.txt), the renders' (requirements-render.txt, beside the first stages), then the
# rest (studies, listening, tests: requirements.txt, which includes both; `make` alone never waits for it)
CORE   ?= $(dir $(STAMP)).core-stamp
RENDER ?= $(dir $(STAMP)).render-stamp
# pipeline/store/deps.py uses the standard library only: it runs before the venv exists
DEPS_PY := $(firstword $(wildcard $(PY)) /usr/bin/python3)
# a minimal Debian 12 has no python3 before the Debian packages: the input checks below then wait for
# Make's restart after $(DEPS_MK), whose rule installs the packages first (.apt-stamp)
NO_PY := $(if $(wildcard $(DEPS_PY)),,1)
# a case is a file pipeline/cases/<CASE>.toml, or a curve's wheel CASE=<curve>/<wheel> (e.g. r150/a1i), whose
# case file the curve stage writes to $(BUILD)/curves/<curve>/cases/<wheel>.toml (artifacts in $(BUILD)/cases/<curve>/<wheel>/)
CURVE_OF = $(if $(findstring /,$(1)),$(firstword $(subst /, ,$(1))))
CASE_FILE = $(if $(findstring /,$(1)),$(BUILD)/curves/$(call CURVE_OF,$(1))/cases/$(notdir $(1)).toml,pipeline/cases/$(1).toml)
CFILE := $(call CASE_FILE,$(CASE))
# the wheel and rail come from the case file (its keys `wheel`, `rail`): WHEEL=/RAIL= only for
# the wheel and rail stages alone, and an error when they disagree with a case target's case
CASE_INPUTS := $(if $(NO_PY),,$(shell $(DEPS_PY) pipeline/store/deps.py --case $(CFILE) 2>&1))
CASE_OK     := $(filter 0,$(.SHELLSTATUS))
WHEEL ?= $(if $(CASE_OK),$(word 1,$(CASE_INPUTS)),c20)
RAIL  ?= $(if $(CASE_OK),$(word 2,$(CASE_INPUTS)),bv50)
CASE_GOALS := all contact greens simulate radiate stability listen report study stability-map
ifneq ($(if $(NO_PY),,$(filter $(CASE_GOALS) $(BUILD)/cases/% $(BUILD)/report/%,$(or $(MAKECMDGOALS),all))),)
  ifeq ($(CASE_OK),)
    $(error CASE=$(CASE): $(CASE_INPUTS))
  endif
  ifneq ($(WHEEL) $(RAIL),$(CASE_INPUTS))
    $(error CASE=$(CASE) names wheel $(word 1,$(CASE_INPUTS)) and rail $(word 2,$(CASE_INPUTS)) ($(CFILE)); \
      WHEEL=$(WHEEL) RAIL=$(RAIL) disagree: drop WHEEL=/RAIL= (the case decides))
  endif
endif
W     := $(BUILD)/wheels/$(WHEEL)
R     := $(BUILD)/rails/$(RAIL)
C     := $(BUILD)/cases/$(CASE)
WFILE := geometry/wheels/$(WHEEL).toml
RFILE := geometry/rails/$(RAIL).toml
STUDY ?= map
# the cases a study runs on: its `cases = [...]` line (read without Python)
# (a study that is not there: none; the study stage names it in one line)
STUDY_CASES = $(shell sed -n 's/^cases *= *\[\(.*\)\].*/\1/p' pipeline/studies/$(STUDY).toml 2>/dev/null | tr -d '",')
MAP_CASES = $(shell sed -n 's/^cases *= *\[\(.*\)\].*/\1/p' pipeline/studies/map.toml | tr -d '",')
export SQUEAL_BUILD_DIR := $(abspath $(BUILD))
export VTK_DEFAULT_OPENGL_WINDOW ?= vtkEGLRenderWindow
export OMP_NUM_THREADS ?= 1
# the stages are separate processes importing the same ~500 modules: let Python cache their bytecode
# (with PYTHONDONTWRITEBYTECODE set, every stage compiles them again, ~2.5 s each)
unexport PYTHONDONTWRITEBYTECODE

# Each stage's sources, DEPS_<stage>: the repository files its code reaches, computed from the
# imports by pipeline/store/deps.py into $(BUILD)/deps.mk, regenerated when a package's .py changes.
DEPS_MK  := $(BUILD)/deps.mk
# the running-surface profiles: data the contact point of every case stage comes from
PROFILES := $(wildcard geometry/profiles/*.csv)
PKG_PY   := $(filter-out tests/% benchmarks/%,$(wildcard */*.py */*/*.py */*/*/*.py))
ifeq ($(filter clean distclean help,$(MAKECMDGOALS)),)
include $(DEPS_MK)
endif
$(DEPS_MK): $(PKG_PY) | .apt-stamp
	@mkdir -p $(@D)
	$(DEPS_PY) pipeline/store/deps.py > $@.tmp && mv $@.tmp $@ || { rm -f $@.tmp; exit 1; }

.DEFAULT_GOAL := all
# `make` (the default case) runs independent stages side by side, one job per core (the rail stage next
# to the wheel modes, the greens stage and the numba warm-up); other goals keep the command line's -j.  nproc counts the cores
# without OMP_NUM_THREADS, which it would honour (a shell with OMP_NUM_THREADS=1 got a serial make)
ifeq ($(filter-out all report,$(or $(MAKECMDGOALS),all)),)
  MAKEFLAGS += -j$(shell env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc 2>/dev/null || echo 1)
  # the contact (~15 s) after the wheel modes, so that the greens stage (~25 s) takes the core the modes
  # leave: Make gives a freed core to the first job it found ready while both were busy, and the contact,
  # needing nothing, would be that job (order only: the contact does not read the modes)
  $(C)/contact.npz: | $(W)/modes.npz
endif
.PHONY: all help setup test validate bench mesh modes rail contact greens simulate radiate stability stability-map listen report study curve check calibrate calibrate-profiles calibrate-coupling calibrate-wheel calibrate-suspension clean distclean FORCE
.DELETE_ON_ERROR:

all: report ## run the default case as far as the stages exist (wheel, rail, contact, greens, simulate, radiate, report)
# `make` also gives a squealing curve's verdict (CURVE, default r75) beside the case and prints its headline last
# (which wheel, f, mode, L_pA at 7.5 m, what would stop it; the page: build/curves/<curve>/verdict.html)
ifneq ($(filter all headline,$(or $(MAKECMDGOALS),all)),)
  CURVE ?= r75
endif
PRINT_HEADLINE = cat $(BUILD)/curves/$(CURVE_NAME)/headline.txt
.PHONY: headline
headline: ## print the headline of CURVE's verdict (default r75, the curve `make` runs) and the page to open
	@$(PRINT_HEADLINE)

help: ## list the targets
	@grep -hE '^[a-z][a-zA-Z_-]*:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/' | awk -F'\t' '{printf "  %-10s %s\n", $$1, $$2}'
	@echo "  variables: CASE=$(CASE) (available: $(notdir $(basename $(wildcard pipeline/cases/*.toml))); a curve's wheel: CASE=<curve>/<wheel>), WHEEL=, RAIL= for mesh/modes/rail alone (default: the case's)"

# --- setup: Debian packages (once), then the venv (again when requirements change)
.apt-stamp: debian-packages.txt
	@missing=$$(for p in $$(grep -v '^#' debian-packages.txt); do dpkg -s $$p >/dev/null 2>&1 || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages: $$missing"; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	fi
	@touch $@

# the venv uses Debian's pip (python3-pip, seen through --system-site-packages: no ensurepip copy) to install
# uv, and uv the requirements (4-5x faster than pip here: ~2 s for the core's 20 packages, where pip takes
# 9-13 s on the setup's critical path).  Every package is pinned (constraints.txt), so both install the same
# versions; numpy and scipy stay Debian's (debian-provided.txt).  pip is the fallback when uv is not there
# or fails.  Neither byte-compiles every file (Python compiles what is imported, when it is).
PIP := $(PY) -m pip install -q --no-compile --disable-pip-version-check -c constraints.txt
UV  := $(PY) -m uv pip install -q --native-tls --python $(PY) -c constraints.txt --override debian-provided.txt
INSTALL = $(UV) -r $(1) || { echo "uv failed: installing $(1) with pip"; $(PIP) -r $(1); }
# the checks import numpy (its version) and pyvista (the renders) and only find the others, which the
# stages import (importing them here is ~1 s each, the core's on the setup's critical path)
MISSING = import importlib.util as u; m = [n for n in '$(1)'.split() if u.find_spec(n) is None]; assert not m, f'not installed: {m}'
$(CORE): requirements-core.txt constraints.txt debian-provided.txt .apt-stamp
	@test -x $(PY) || /usr/bin/python3 -m venv --system-site-packages --without-pip .venv
	$(PIP) uv || echo "no uv: installing with pip"
	$(call INSTALL,requirements-core.txt)
	$(PY) -c "$(call MISSING,numba rocket_fft pydantic matplotlib tqdm); import numpy; assert numpy.__version__.startswith('1.24'), numpy.__version__; assert numpy.__file__.startswith('/usr/lib/python3/'), numpy.__file__"
	@touch $@

# the renders' packages, beside the first stages: the installed core packages satisfy the pins, so
# nothing a running stage imports is replaced
$(RENDER): requirements-render.txt $(CORE)
	$(call INSTALL,requirements-render.txt)
	$(PY) -c "import pyvista"
	@touch $@

# the rest (studies, listening, tests), for the goals that need it
$(STAMP): requirements.txt $(RENDER)
	$(call INSTALL,requirements.txt)
	$(PY) -c "$(call MISSING,dolfinx slepc4py gmsh dask distributed pyfar pytest)"
	@touch $@

setup: $(STAMP) ## install Debian packages and the Python venv (stamp files; reruns only when the lists change)

check: | $(STAMP) ## validate the CASE file and its wheel and rail (or WHEEL=, RAIL=) only; STUDY=<name>: the study file (a line study: its CSV of curves); CURVE=<name>: the curve, its vehicle, wheel and rail, the steady curving
	$(if $(filter command line,$(origin STUDY)),$(PY) -m pipeline.study.check $(STUDY),$(if $(CURVE),$(PY) -m pipeline check --curve $(CURVE),$(PY) -m pipeline check --wheel $(WHEEL) --rail $(RAIL) --case $(CASE)))

# --- wheel stages
$(W)/mesh.json: $(WFILE) $(DEPS_mesh) | $(CORE)
	$(PY) -m pipeline mesh --wheel $(WHEEL)

$(W)/modes.npz: $(W)/mesh.json $(WFILE) $(DEPS_modes) | $(CORE)
	$(PY) -m pipeline modes --wheel $(WHEEL)

# one llvmpipe (Mesa) render thread: the same pixels, ~7 % less CPU (it runs beside other stages)
$(W)/shapes/gallery.png: $(W)/modes.npz $(WFILE) $(DEPS_shapes) | $(RENDER)
	LP_NUM_THREADS=1 $(PY) -m pipeline shapes --wheel $(WHEEL)

# --- rail and contact stages (the greens stage needs the rail's section mesh, not rail.npz: it meshes
# the section as the rail stage does and runs beside it)
$(R)/rail.npz: $(RFILE) $(DEPS_rail) | $(CORE)
	$(PY) -m pipeline rail --rail $(RAIL)

$(C)/contact.npz: $(CFILE) $(WFILE) $(RFILE) $(PROFILES) $(DEPS_contact) | $(CORE)
	$(PY) -m pipeline contact --case $(CASE)

# numba's compiled code of the simulate stage, made while the rail stage runs (pipeline/stages/warm.py; once per build
# folder: a stage whose code changed since compiles for itself, as without it); after the wheel modes, so that with
# parallel jobs it never holds up the greens stage's inputs
JIT := $(BUILD)/.numba-warm
$(JIT): | $(CORE) $(W)/modes.npz
	$(PY) -m pipeline.stages.warm && touch $@

$(C)/greens.npz: $(CFILE) $(WFILE) $(RFILE) $(PROFILES) $(W)/modes.npz $(DEPS_greens) | $(CORE)
	$(PY) -m pipeline greens --case $(CASE)

$(C)/simulate.npz: $(CFILE) $(WFILE) $(RFILE) $(C)/contact.npz $(C)/greens.npz $(DEPS_simulate) | $(CORE) $(JIT)
	$(PY) -m pipeline simulate --case $(CASE)

$(C)/radiate.npz: $(CFILE) $(WFILE) $(RFILE) $(PROFILES) $(W)/modes.npz $(C)/simulate.npz $(DEPS_radiate) | $(CORE)
	$(PY) -m pipeline radiate --case $(CASE)

$(C)/stability.npz: $(CFILE) $(WFILE) $(RFILE) $(C)/contact.npz $(C)/greens.npz $(DEPS_stability) | $(CORE)
	$(PY) -m pipeline stability --case $(CASE)

# the receiver: the case's [listener] table, or DISTANCE=, HEIGHT= (m); ALLOW_SILENT=1 for a case that does not
# squeal.  A run with these always runs and leaves listen.override, so that the next plain run restores the case's own
LISTEN_ARGS = $(strip $(if $(DISTANCE),--distance $(DISTANCE)) $(if $(HEIGHT),--height $(HEIGHT)) $(if $(ALLOW_SILENT),--allow-silent))
$(C)/listen.npz: $(CFILE) $(WFILE) $(RFILE) $(C)/radiate.npz $(C)/simulate.npz $(DEPS_listen) $(if $(LISTEN_ARGS)$(wildcard $(C)/listen.override),FORCE) | $(STAMP)
	$(PY) -m pipeline listen --case $(CASE) $(LISTEN_ARGS)
	@$(if $(LISTEN_ARGS),touch,rm -f) $(C)/listen.override

FORCE:

# the listening section is in the report when `make listen` has run (as the studies)
# parallel Make starts the jobs in the order of these lists (depth first, the rules read in this
# order; the recipe's rule has none of its own, else its prerequisites would come first; the
# order-only ones are here for that order only): the wheel mesh, the renders' pip step, the rail, the wheel
# modes, the greens stage, the numba warm-up, the contact, the renders, simulate -> radiate
$(BUILD)/report/$(CASE)/report.md: | $(W)/mesh.json $(RENDER)
$(BUILD)/report/$(CASE)/report.md: $(CFILE) $(R)/rail.npz $(W)/modes.npz $(C)/greens.npz | $(JIT)
$(BUILD)/report/$(CASE)/report.md: $(C)/contact.npz $(W)/shapes/gallery.png $(C)/simulate.npz $(C)/radiate.npz $(WFILE) $(RFILE) $(C)/stability.npz $(DEPS_report) $(wildcard $(BUILD)/studies/*/summary.md) $(wildcard $(C)/listen*.npz)
$(BUILD)/report/$(CASE)/report.md:
	$(PY) -m pipeline report --case $(CASE)

mesh: $(W)/mesh.json ## Gmsh cross-section of WHEEL (default: CASE's wheel) -> build/wheels/WHEEL/section.msh
modes: $(W)/modes.npz $(W)/shapes/gallery.png ## wheel modes n = 0..N (dolfinx+SLEPc), mode table and 3D renders
rail: $(R)/rail.npz ## rail section, waveguide FE, dispersion, receptances (RAIL=, default: CASE's rail)
contact: $(C)/contact.npz ## contact of CASE: gap, NORM table, compliance, friction curves
greens: $(C)/greens.npz ## Green's functions of CASE: wheel (Kropp + modal filters), moving rail kernel
simulate: $(C)/simulate.npz ## time-domain interaction of CASE: force histories, L_F2, dominant frequency
radiate: $(C)/radiate.npz ## sound power of CASE's wheel under the simulated forces: W(f), L_W, per harmonic, unit-force curves
stability: $(C)/stability.npz ## frequency-domain stability screen of CASE: closed-loop poles, growth rates, mode labels
listen: $(C)/listen.npz ## what a listener hears: L_p, L_pA, 1/3 octaves, a calibrated WAV of the squeal; DISTANCE=, HEIGHT=, ALLOW_SILENT=1
report: $(BUILD)/report/$(CASE)/report.md ## one Markdown report of CASE (its wheel and rail come from the case file)

# --- studies (SPEC 7): the cases' artifacts first, then the study on Dask (resumes when interrupted)
study: | $(STAMP) ## parameter study STUDY=map|damping|contact|<line> on Dask -> build/studies/STUDY/; QUICK=1, WORKERS=N, SCHEDULER=tcp://host:port
	@for c in $(STUDY_CASES); do $(MAKE) --no-print-directory contact greens CASE=$$c || exit 1; done
	$(PY) -m pipeline study --study $(STUDY) $(if $(QUICK),--quick) $(if $(WORKERS),--workers $(WORKERS)) $(if $(SCHEDULER),--scheduler $(SCHEDULER))

stability-map: | $(STAMP) ## the stability screen over STUDY's grid (seconds; needs the cases' contact and greens) [QUICK=1]
	@for c in $(STUDY_CASES); do $(MAKE) --no-print-directory contact greens CASE=$$c || exit 1; done
	$(PY) -m pipeline stability_map --study $(STUDY) $(if $(QUICK),--quick)

# --- a curve's verdict: CURVE=<name> (pipeline/curves/<name>.toml) or CURVE=<path> (a curve file anywhere, e.g.
# outside the repository: a value with a / or ending in .toml).  The curve names the vehicle, looked up beside
# the curve file first, then in geometry/vehicles/; the vehicle names the wheel, the curve the rail.  Results in
# $(BUILD)/curves/<the curve file's stem>/.  The wheel modes and the rail first (their own rules), then the
# curve stage: curving, the wheels' cases, contact/greens/screen for every wheel, the time loop, radiation and
# listening for the unstable ones, the what-ifs
CURVE   ?=
CURVE_IS_PATH = $(or $(findstring /,$(CURVE)),$(filter %.toml,$(CURVE)))
CURVE_F  = $(if $(CURVE_IS_PATH),$(CURVE),pipeline/curves/$(CURVE).toml)
CURVE_NAME = $(basename $(notdir $(CURVE_F)))
TOML_KEY = $(shell sed -n 's/^$(1) *= *"\([^"]*\)".*/\1/p' $(2) 2>/dev/null | head -1)
VEHICLE  = $(call TOML_KEY,vehicle,$(CURVE_F))
VEHICLE_F = $(firstword $(wildcard $(dir $(CURVE_F))$(VEHICLE).toml) geometry/vehicles/$(VEHICLE).toml)
CURVE_WHEEL = $(or $(call TOML_KEY,wheel,$(VEHICLE_F)),c20)
CURVE_RAIL  = $(or $(call TOML_KEY,rail,$(CURVE_F)),bv50)
# the curve's vehicle, wheel and rail files are there and the vehicle's name is its file's (pipeline/store/deps.py
# --curve), else one line naming the file and key that asked, before any work (a missing wheel file was
# Make's "No rule to make target")
ifneq ($(if $(NO_PY),,$(CURVE)),)
  ifneq ($(filter curve check $(BUILD)/curves/%,$(MAKECMDGOALS)),)
    CURVE_INPUTS := $(shell $(DEPS_PY) pipeline/store/deps.py --curve $(CURVE_F) 2>&1)
    ifneq ($(.SHELLSTATUS),0)
      $(error CURVE=$(CURVE): $(CURVE_INPUTS))
    endif
  endif
endif
$(BUILD)/curves/$(CURVE_NAME)/verdict.csv: $(CURVE_F) $(wildcard $(VEHICLE_F)) geometry/wheels/$(CURVE_WHEEL).toml geometry/rails/$(CURVE_RAIL).toml $(PROFILES) $(wildcard pipeline/climates/*.toml) $(DEPS_curve) | $(STAMP)
	@$(MAKE) --no-print-directory $(BUILD)/wheels/$(CURVE_WHEEL)/modes.npz $(BUILD)/rails/$(CURVE_RAIL)/rail.npz \
	  WHEEL=$(CURVE_WHEEL) RAIL=$(CURVE_RAIL) CASE=default
	$(PY) -m pipeline curve --curve $(if $(CURVE_IS_PATH),$(abspath $(CURVE_F)),$(CURVE)) $(if $(NO_WHAT_IFS),--no-what-ifs)

# `make`: the curve beside the case, after the wheel modes, rail and numba warm-up the case builds (never twice at once)
# and its headline last, once the report and the verdict are done (a file, so that `make -q` stays true; shown
# again when the verdict changes)
ifeq ($(or $(MAKECMDGOALS),all),all)
all: $(BUILD)/curves/$(CURVE_NAME)/.headline-shown
$(BUILD)/curves/$(CURVE_NAME)/verdict.csv: | $(W)/modes.npz $(R)/rail.npz $(JIT)
$(BUILD)/curves/$(CURVE_NAME)/.headline-shown: $(BUILD)/curves/$(CURVE_NAME)/verdict.csv | $(BUILD)/report/$(CASE)/report.md
	@$(PRINT_HEADLINE) && touch $@
endif

curve: ## the verdict of CURVE=<name or path to a curve file>: which wheel squeals, f, L_pA, what would stop it -> build/curves/<curve>/verdict.{csv,md}, bogie.png
	@test -n "$(CURVE)" || { echo "make curve: name the curve, CURVE=<name> (one of: $(notdir $(basename $(wildcard pipeline/curves/*.toml)))) or CURVE=<path to a curve file>" >&2; exit 2; }
	@test -f "$(CURVE_F)" || { echo "make curve: $(CURVE_F): no such curve file$(if $(CURVE_IS_PATH),, (available: $(notdir $(basename $(wildcard pipeline/curves/*.toml)))))" >&2; exit 2; }
	@$(MAKE) --no-print-directory $(BUILD)/curves/$(CURVE_NAME)/verdict.csv CURVE=$(CURVE)

# --- calibration of what the thesis does not give (docs/validation, "Calibration"); in this order,
# each writes its values into the data files (comments kept); none runs in `make` or `make test`
calibrate: calibrate-wheel calibrate-profiles calibrate-suspension ## all calibrations in order: the wheel section, its running surface, then the damping (~40 min)
calibrate-profiles: | $(STAMP) ## write geometry/profiles/ (S1002, C20, BV50, 60E1 new; C20 and BV50 worn, fitted to thesis [4.1])
	$(PY) -m pipeline.validation.calibrate_profiles
calibrate-coupling: | $(STAMP) ## scan the (2,0,a)/(3,0,a) coupling zero points with the stability screen (the wheel fit's targets)
	@for c in $(MAP_CASES); do $(MAKE) --no-print-directory contact greens CASE=$$c || exit 1; done
	$(PY) -m pipeline.validation.calibrate_coupling --study map
calibrate-wheel: | $(STAMP) ## fit the C20 section to the 34 reference frequencies and the coupling zero points (~30 min)
	$(PY) -m pipeline.validation.calibrate_wheel --wheel c20 --write
calibrate-suspension: | $(STAMP) ## fit the C20's vertical suspension damping to the reference's low-frequency threshold at -5 mm
	@for c in $(MAP_CASES); do $(MAKE) --no-print-directory contact greens CASE=$$c || exit 1; done
	$(PY) -m pipeline.validation.calibrate_suspension --study map --write

# --- quality
# in random order (pytest-randomly): a new seed every run, printed first; SEED=<n> repeats an order
test: | $(STAMP) ## run the test suite in random order (fast; validation tests are skipped); SEED=<n> repeats an order
	@seed=$${SEED:-$$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}; \
	echo "make test: the tests in random order, seed $$seed (SEED=$$seed make test repeats it)"; \
	$(PY) -m pytest -q --durations=15 -p randomly --randomly-seed=$$seed tests

# the writers first (pipeline/validation/writers/registry.py; each builds what it needs through Make, the
# cached runs they share with the tests -- the limit-cycle tables, the 3D wheel -- are then up to date), then
# the slow tests asserting the limits the fragments state; both run, and validate fails if either does
validate: | $(STAMP) ## write docs/validation/ and docs/validation.md (the writers), then run the slow validation tests
	@status=0; \
	$(PY) -m pipeline.validation.writers || status=1; \
	$(PY) -m pytest -q --validation -m validation tests || status=1; \
	exit $$status

bench: | $(STAMP) ## run the benchmarks and write docs/benchmarks.md
	$(PY) -m benchmarks

clean: ## remove build outputs (keeps the venv)
	rm -rf $(BUILD) meshes/*.msh

distclean: clean ## also remove the venv and setup stamps
	rm -rf .venv .apt-stamp
