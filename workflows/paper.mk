# The paper's whole study as one campaign (included by workflows/Makefile):
#
#   make -C workflows paper BIN=<build dir> [PAPER_OUT=../runs/paper] [REALISATIONS=N]
#
# Every shape of PAPER_SHAPES runs the campaign of its config PAPER_CONFIGS/paper-<shape>.toml
# (prepare, load with static checkpoints, fabric, probes, voxels, permeability: the `campaign`
# target) into PAPER_OUT/<shape>/r<k>, one folder per realisation k = 1..REALISATIONS
# (realisation k runs the config with dem.seed raised by k - 1; campaign.py realisation). Then
# plots/paper_report.py draws every paper figure from those folders into PAPER_OUT/figures and
# writes PAPER_OUT/comparison.md with the numbers. Each campaign resumes where it stopped, so
# rerunning after a kill redoes only what is missing; make -j2 runs two stages at a time.

PAPER_OUT     ?= ../runs/paper
PAPER_EXPORT  ?= ../docs/paper-size
PAPER_SHAPES  ?= spheres ovoids-0.8 ovoids-0.625 ovoids-0.5
PAPER_CONFIGS ?= configs
REALISATIONS  ?= 1

paper_goals := paper paper-runs paper-figures paper-export paper-export-partial paper-status
paper_realisations := $(shell seq 1 $(REALISATIONS) 2>/dev/null)
ifneq ($(filter $(paper_goals),$(MAKECMDGOALS)),)
ifeq ($(strip $(paper_realisations)),)
$(error REALISATIONS = '$(REALISATIONS)': expected an integer >= 1)
endif
$(foreach s,$(PAPER_SHAPES),$(if $(wildcard $(PAPER_CONFIGS)/paper-$(s).toml),,\
  $(error PAPER_SHAPES names '$(s)', but $(PAPER_CONFIGS)/paper-$(s).toml does not exist)))
endif

# Runs are <shape>/r<k>; their make names <shape>-r<k>; their labels the shape alone when there
# is one realisation (paper_report.py writes 'ovoids-0.5' as 'alpha = 0.5').
paper_runs    := $(foreach s,$(PAPER_SHAPES),$(foreach k,$(paper_realisations),$(s)/r$(k)))
paper_name     = $(subst /,-,$(1))
paper_config   = $(PAPER_OUT)/configs/$(call paper_name,$(1)).toml
paper_label    = $(if $(filter 1,$(REALISATIONS)),$(firstword $(subst /, ,$(1))),$(call paper_name,$(1)))
paper_export_name = $(paper_label)
PAPER_REPORT  := $(PAPER_OUT)/comparison.md

define paper_run_rules
$(call paper_config,$(1)): $(PAPER_CONFIGS)/paper-$(firstword $(subst /, ,$(1))).toml
	$(PYTHON) campaign.py realisation $$< $(patsubst r%,%,$(lastword $(subst /, ,$(1)))) $$@

paper-run-$(call paper_name,$(1)): $(call paper_config,$(1))
	$(MAKE) campaign CONFIG=$(abspath $(call paper_config,$(1))) OUT=$(abspath $(PAPER_OUT)/$(1))
endef
$(foreach r,$(paper_runs),$(eval $(call paper_run_rules,$(r))))

.PHONY: $(paper_goals) $(foreach r,$(paper_runs),paper-run-$(call paper_name,$(r)))

# make -j starts the runs in this order: the costliest shape first, so that the longest chain
# (alpha = 0.5: about 2 h of preparation and 10 h of load with verified copies on one core, against
# 2 h for all of the spheres' DEM) does not wait for the others to free a job slot; the report
# keeps PAPER_SHAPES' order.
PAPER_COST_ORDER := ovoids-0.5 ovoids-0.625 ovoids-0.8 spheres
paper_run_order = $(filter $(PAPER_SHAPES),$(PAPER_COST_ORDER)) $(filter-out $(PAPER_COST_ORDER),$(PAPER_SHAPES))
paper-runs: $(foreach s,$(paper_run_order),$(foreach k,$(paper_realisations),paper-run-$(call paper_name,$(s)/r$(k))))

# The figures wait for every run: a second make, so that -j cannot start them early.
paper: paper-runs
	$(MAKE) paper-figures

$(PAPER_REPORT): $(foreach r,$(paper_runs),$(PAPER_OUT)/$(r)/report.md) $(wildcard plots/*.py)
	$(PYTHON) plots/paper_report.py $(PAPER_OUT) \
	  $(foreach r,$(paper_runs),$(call paper_label,$(r))=$(abspath $(PAPER_OUT)/$(r)))

paper-figures: $(PAPER_REPORT)

# Where each run of the study stands (the `status` of workflows/Makefile, run by run).
paper-status:
	@$(foreach r,$(paper_runs),test ! -f $(call paper_config,$(r)) && echo "$(abspath $(PAPER_OUT)/$(r)): not started" || \
	  $(MAKE) -s --no-print-directory status CONFIG=$(abspath $(call paper_config,$(r))) OUT=$(abspath $(PAPER_OUT)/$(r));)

# The run's small results where the docs keep them (paper_export.py): per run its history, fabric
# series, probes, static states, void and permeability series, preparation log and stage times,
# then the comparison and its figures; a folder per shape (per shape and realisation with several).
paper-export: $(PAPER_REPORT)
	$(PYTHON) paper_export.py $(PAPER_OUT) $(PAPER_EXPORT) \
	  $(foreach r,$(paper_runs),$(call paper_export_name,$(r))=$(abspath $(PAPER_OUT)/$(r)))

# What a study still running has finished so far, into PAPER_EXPORT (give it a folder of its own,
# e.g. PAPER_EXPORT=../docs/paper-size/make-paper-<date>): the same files, of the checkpoints done.
paper-export-partial:
	$(PYTHON) paper_export.py --partial $(PAPER_OUT) $(PAPER_EXPORT) \
	  $(foreach r,$(paper_runs),$(call paper_export_name,$(r))=$(abspath $(PAPER_OUT)/$(r)))
