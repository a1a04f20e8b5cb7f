# Curve squeal pipeline: geometry -> wheel modes -> ... (see README).
# `make` sets up the machine and runs the default case as far as the stages
# exist; `make test` sets up and runs the test suite.  Select inputs with
# WHEEL=<name> (geometry/wheels/<name>.toml), RAIL=<name> (geometry/rails/),
# CASE=<name> (pipeline/cases/), STUDY=<name> (pipeline/studies/).

WHEEL ?= c20
RAIL  ?= bv50
CASE  ?= default
BUILD ?= build
PY    := .venv/bin/python
STAMP := .venv/.setup-stamp
W     := $(BUILD)/wheels/$(WHEEL)
R     := $(BUILD)/rails/$(RAIL)
C     := $(BUILD)/cases/$(CASE)
WFILE := geometry/wheels/$(WHEEL).toml
RFILE := geometry/rails/$(RAIL).toml
CFILE := pipeline/cases/$(CASE).toml
STUDY ?= map
# the cases a study runs on: its `cases = [...]` line (read without Python)
STUDY_CASES = $(shell sed -n 's/^cases *= *\[\(.*\)\].*/\1/p' pipeline/studies/$(STUDY).toml | tr -d '",')
export SQUEAL_BUILD_DIR := $(abspath $(BUILD))
export VTK_DEFAULT_OPENGL_WINDOW ?= vtkEGLRenderWindow
export OMP_NUM_THREADS ?= 1

GEOMETRY_SRC := geometry/wheel.py geometry/outline.py geometry/mesher.py
MODES_SRC    := solvers/axisym.py solvers/classify.py solvers/wheelset.py pipeline/wheel_stage.py
SHAPES_SRC   := postprocess/mode_shapes.py
RAIL_SRC     := geometry/rail.py geometry/mesher.py solvers/waveguide.py solvers/rail_response.py pipeline/rail_stage.py
CONTACT_SRC  := $(wildcard solvers/contact/*.py) pipeline/contact_stage.py geometry/wheel.py geometry/rail.py
GREENS_SRC   := solvers/green.py solvers/receptance.py solvers/rail_response.py solvers/moving_kernel.py pipeline/rail_kernel.py pipeline/greens_stage.py
SIM_SRC      := solvers/interaction.py solvers/green.py solvers/partitioned.py pipeline/simulate_stage.py postprocess/spectra.py
STAB_SRC     := solvers/stability.py solvers/interaction.py solvers/green.py solvers/partitioned.py pipeline/stability_stage.py
RADIATE_SRC  := postprocess/radiation.py postprocess/force_radiation.py postprocess/spectra.py solvers/receptance.py geometry/wheel.py pipeline/radiate_stage.py
LISTEN_SRC   := postprocess/listener.py postprocess/audio.py postprocess/spectra.py pipeline/listen_stage.py postprocess/plots/listen.py

.DEFAULT_GOAL := all
.PHONY: all help setup test validate bench mesh modes rail contact greens simulate radiate stability stability-map listen report study check clean distclean FORCE
.DELETE_ON_ERROR:

all: report ## run the default case as far as the stages exist (wheel, rail, contact, greens, simulate, radiate, report)

help: ## list the targets
	@grep -hE '^[a-z][a-zA-Z_-]*:.*## ' $(MAKEFILE_LIST) | sed 's/:.*## /\t/' | awk -F'\t' '{printf "  %-10s %s\n", $$1, $$2}'
	@echo "  variables: WHEEL=$(WHEEL) (available: $(notdir $(basename $(wildcard geometry/wheels/*.toml))))"

# --- setup: Debian packages (once), then the venv (again when requirements change)
.apt-stamp: debian-packages.txt
	@missing=$$(for p in $$(grep -v '^#' debian-packages.txt); do dpkg -s $$p >/dev/null 2>&1 || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages: $$missing"; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi
	@touch $@

$(STAMP): requirements.txt constraints.txt .apt-stamp
	@test -x $(PY) || /usr/bin/python3 -m venv --system-site-packages .venv
	$(PY) -m pip install -q --disable-pip-version-check -c constraints.txt -r requirements.txt
	$(PY) -c "import dolfinx, slepc4py, gmsh, numba, rocket_fft, pyvista, numpy, dask, distributed, pydantic; assert numpy.__version__.startswith('1.24'), numpy.__version__"
	@touch $@

setup: $(STAMP) ## install Debian packages and the Python venv (stamp files; reruns only when the lists change)

check: | $(STAMP) ## validate the WHEEL, RAIL and CASE files only
	$(PY) -m pipeline check --wheel $(WHEEL) --rail $(RAIL) --case $(CASE)

# --- wheel stages
$(W)/mesh.json: $(WFILE) $(GEOMETRY_SRC) | $(STAMP)
	$(PY) -m pipeline mesh --wheel $(WHEEL)

$(W)/modes.npz: $(W)/mesh.json $(WFILE) $(MODES_SRC) | $(STAMP)
	$(PY) -m pipeline modes --wheel $(WHEEL)

$(W)/shapes/gallery.png: $(W)/modes.npz $(SHAPES_SRC) | $(STAMP)
	$(PY) -m pipeline shapes --wheel $(WHEEL)

# --- rail and contact stages
$(R)/rail.npz: $(RFILE) $(RAIL_SRC) | $(STAMP)
	$(PY) -m pipeline rail --rail $(RAIL)

$(C)/contact.npz: $(CFILE) $(WFILE) $(RFILE) $(CONTACT_SRC) | $(STAMP)
	$(PY) -m pipeline contact --case $(CASE)

$(C)/greens.npz: $(CFILE) $(W)/modes.npz $(R)/rail.npz $(GREENS_SRC) | $(STAMP)
	$(PY) -m pipeline greens --case $(CASE)

$(C)/simulate.npz: $(CFILE) $(C)/contact.npz $(C)/greens.npz $(SIM_SRC) | $(STAMP)
	$(PY) -m pipeline simulate --case $(CASE)

$(C)/radiate.npz: $(CFILE) $(W)/modes.npz $(C)/simulate.npz $(RADIATE_SRC) | $(STAMP)
	$(PY) -m pipeline radiate --case $(CASE)

$(C)/stability.npz: $(CFILE) $(C)/contact.npz $(C)/greens.npz $(STAB_SRC) | $(STAMP)
	$(PY) -m pipeline stability --case $(CASE)

# the receiver: the case's [listener] table, or DISTANCE=, HEIGHT= (m); ALLOW_SILENT=1 for a case that does not
# squeal.  A run with these always runs and leaves listen.override, so that the next plain run restores the case's own
LISTEN_ARGS = $(strip $(if $(DISTANCE),--distance $(DISTANCE)) $(if $(HEIGHT),--height $(HEIGHT)) $(if $(ALLOW_SILENT),--allow-silent))
$(C)/listen.npz: $(CFILE) $(WFILE) $(C)/radiate.npz $(C)/simulate.npz $(LISTEN_SRC) $(if $(LISTEN_ARGS)$(wildcard $(C)/listen.override),FORCE) | $(STAMP)
	$(PY) -m pipeline listen --case $(CASE) $(LISTEN_ARGS)
	@$(if $(LISTEN_ARGS),touch,rm -f) $(C)/listen.override

FORCE:

# the listening section is in the report when `make listen` has run (as the studies)
$(BUILD)/report/$(CASE)/report.md: $(CFILE) $(W)/modes.npz $(W)/shapes/gallery.png $(R)/rail.npz $(C)/contact.npz $(C)/greens.npz $(C)/simulate.npz $(C)/radiate.npz pipeline/report.py pipeline/study/report.py $(wildcard $(BUILD)/studies/*/summary.md) $(wildcard $(C)/listen.npz) | $(STAMP)
	$(PY) -m pipeline report --case $(CASE)

mesh: $(W)/mesh.json ## Gmsh cross-section of WHEEL -> build/wheels/WHEEL/section.msh
modes: $(W)/modes.npz $(W)/shapes/gallery.png ## wheel modes n = 0..N (dolfinx+SLEPc), mode table and 3D renders
rail: $(R)/rail.npz ## rail section, waveguide FE, dispersion, receptances (RAIL=bv50)
contact: $(C)/contact.npz ## contact of CASE: gap, NORM table, compliance, friction curves
greens: $(C)/greens.npz ## Green's functions of CASE: wheel (Kropp + modal filters), moving rail kernel
simulate: $(C)/simulate.npz ## time-domain interaction of CASE: force histories, L_F2, dominant frequency
radiate: $(C)/radiate.npz ## sound power of CASE's wheel under the simulated forces: W(f), L_W, per harmonic, unit-force curves
stability: $(C)/stability.npz ## frequency-domain stability screen of CASE: closed-loop poles, growth rates, mode labels
listen: $(C)/listen.npz ## what a listener hears: L_p, L_pA, 1/3 octaves, a calibrated WAV of the squeal; DISTANCE=, HEIGHT=, ALLOW_SILENT=1
report: $(BUILD)/report/$(CASE)/report.md ## one Markdown report of CASE (WHEEL, RAIL must be the case's)

# --- studies (SPEC 7): the cases' artifacts first, then the study on Dask (resumes when interrupted)
study: | $(STAMP) ## parameter study STUDY=map|damping|contact on Dask -> build/studies/STUDY/; QUICK=1, WORKERS=N, SCHEDULER=tcp://host:port
	@for c in $(STUDY_CASES); do $(MAKE) --no-print-directory contact greens CASE=$$c || exit 1; done
	$(PY) -m pipeline study --study $(STUDY) $(if $(QUICK),--quick) $(if $(WORKERS),--workers $(WORKERS)) $(if $(SCHEDULER),--scheduler $(SCHEDULER))

stability-map: | $(STAMP) ## the stability screen over STUDY's grid (seconds; needs the cases' contact and greens) [QUICK=1]
	@for c in $(STUDY_CASES); do $(MAKE) --no-print-directory contact greens CASE=$$c || exit 1; done
	$(PY) -m pipeline stability_map --study $(STUDY) $(if $(QUICK),--quick)

# --- quality
test: | $(STAMP) ## run the test suite (fast; validation tests are skipped)
	$(PY) -m pytest -q tests

validate: | $(STAMP) ## run the slower validation suite and write docs/validation.md
	$(PY) -m pytest -q --validation tests
	$(PY) -m pipeline.docs validation

bench: | $(STAMP) ## run the benchmarks and write docs/benchmarks.md
	$(PY) -m benchmarks

clean: ## remove build outputs (keeps the venv)
	rm -rf $(BUILD) meshes/*.msh

distclean: clean ## also remove the venv and setup stamps
	rm -rf .venv .apt-stamp
