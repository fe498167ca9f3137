# The studies behind docs/charts and the methods' speed/accuracy tables (included by
# workflows/Makefile, so every target runs as make -C workflows <target> BIN=<build dir>).
# Each study is a script of this folder that runs its stages through runner.py (cached: an
# interrupted study continues where it stopped; a failed stage stops it with the stage's log) and
# draws its chart with the plotting library's readers (workflows/plots/readers.py). The folder's
# README.md lists them with what they measure and how long they take.

.PHONY: chart-prepare-cycles chart-dem-rate chart-dem-increment chart-dem-time-step chart-dem-time-step-ovoid \
        chart-dem-relax-methods chart-dem-quasi-static chart-dem-dempla chart-dem-dempla-ovoids chart-dem-behaviours \
        chart-preparation-study prep-study-spheres prep-study-ovoids-0.625 prep-study-ovoids-0.5

# Rate convergence of continuous loading (docs/charts/dem_rate.png, about 25 min on 2 cores)
# and of incremental loading (docs/charts/dem_increment.png, about 30 min on one core):
#   make -C workflows chart-dem-rate chart-dem-increment BIN=<build dir>
# Finished runs in CHART_RUN are reused, so an interrupted chart continues.
CHART_OUT ?= ../docs/charts
CHART_RUN ?= ../runs/chart-dem-rate
# e against compaction cycle for the four paper-size preparations, from their logs.
PREPARE_LOGS ?= ../docs/paper-size/prepare
chart-prepare-cycles:
	mkdir -p $(CHART_OUT)
	$(PYTHON) studies/chart_prepare_cycles.py $(CHART_OUT) 0.556 0.003 spheres=$(PREPARE_LOGS)/spheres.log \
	  "alpha 0.8=$(PREPARE_LOGS)/ovoids-0.8.log" "alpha 0.625=$(PREPARE_LOGS)/ovoids-0.625.log" \
	  "alpha 0.5=$(PREPARE_LOGS)/ovoids-0.5.log"

chart-dem-rate: $(DEM_OUT)/prepared.h5
	mkdir -p $(CHART_RUN) $(CHART_OUT)
	$(PYTHON) studies/chart_dem_rate.py $(BIN)/dem/aniso-dem $(DEM_OUT)/prepared.h5 $(CHART_RUN) $(CHART_OUT) 0.1

chart-dem-increment: $(DEM_OUT)/prepared.h5
	mkdir -p $(CHART_RUN)/increments $(CHART_OUT)
	$(PYTHON) studies/chart_dem_increment.py $(BIN)/dem/aniso-dem $(DEM_OUT)/prepared.h5 $(CHART_RUN)/increments \
	  $(CHART_OUT) 0.05 $(CHART_RUN)

# Time step against accuracy of the loading (docs/charts/dem_time_step.png, about 10 min on 2 cores):
#   make -C workflows chart-dem-time-step BIN=<build dir>
chart-dem-time-step: $(DEM_OUT)/prepared.h5
	mkdir -p $(CHART_RUN)/time-step $(CHART_OUT)
	$(PYTHON) studies/chart_dem_time_step.py $(BIN)/dem/aniso-dem $(DEM_OUT)/prepared.h5 $(CHART_RUN)/time-step \
	  $(CHART_OUT) 0.1

# The same for ovoids (docs/charts/dem_time_step_ovoid.png, about 10 min on 2 cores) from a
# prepared ovoid assembly, e.g. the demo config with --set dem.particles.aspect_ratio=0.625
# --set dem.prepare.initial_solid_fraction=0.35:
#   make -C workflows chart-dem-time-step-ovoid BIN=<build dir> ALPHA_PREPARED=<prepared.h5>
chart-dem-time-step-ovoid:
	@test -n "$(ALPHA_PREPARED)" || { echo "set ALPHA_PREPARED to a prepared ovoid assembly" >&2; exit 2; }
	mkdir -p $(CHART_RUN)/time-step-ovoid $(CHART_OUT)
	$(PYTHON) studies/chart_dem_time_step_ovoid.py $(BIN)/dem/aniso-dem $(ALPHA_PREPARED) \
	  $(CHART_RUN)/time-step-ovoid $(CHART_OUT)

# Static states (docs/methods/dem.md, "Static states" and "Quasi-static loading"): damped
# relaxation against FIRE on checkpoints of the demo's spheres and of 1000 alpha = 0.5 ovoids
# (about 1.5 h on one core), and the quasi-static loading's convergence in its increment and
# tolerance against continuous loading, three realisations to 4% (about 2 h on 2 cores):
#   make -C workflows chart-dem-relax-methods chart-dem-quasi-static BIN=<build dir>
RELAX_STRAINS ?= 0.001,0.005,0.01,0.02,0.05,0.1,0.2,0.3
$(CHART_RUN)/seed%/prepared.h5:
	$(BIN)/dem/aniso-dem prepare --config configs/demo.toml --set dem.seed=$* --set dem.output_dir=$(@D)

$(CHART_RUN)/ovoids-0.5/prepared.h5:
	$(BIN)/dem/aniso-dem prepare --config configs/paper-ovoids-0.5.toml --set dem.particles.count=1000 \
	  --set dem.load.behaviour=inertial --set dem.output_dir=$(@D)

chart-dem-relax-methods: $(CHART_RUN)/seed1/prepared.h5 $(CHART_RUN)/ovoids-0.5/prepared.h5
	mkdir -p $(CHART_RUN)/relax-methods $(CHART_OUT)
	$(PYTHON) studies/chart_dem_relax_methods.py $(BIN) $(CHART_RUN)/relax-methods $(CHART_OUT) $(RELAX_STRAINS) 1 \
	  spheres=$(CHART_RUN)/seed1/prepared.h5
	RELAX_METHODS=fire_m0.01,fire_m0.1,damped_m0.5 $(PYTHON) studies/chart_dem_relax_methods.py $(BIN) \
	  $(CHART_RUN)/relax-methods $(CHART_OUT) $(RELAX_STRAINS) 1 ovoids_0.5=$(CHART_RUN)/ovoids-0.5/prepared.h5

chart-dem-quasi-static: $(CHART_RUN)/seed1/prepared.h5 $(CHART_RUN)/seed2/prepared.h5 $(CHART_RUN)/seed3/prepared.h5
	mkdir -p $(CHART_RUN)/quasi-static $(CHART_OUT)
	$(PYTHON) studies/chart_dem_quasi_static.py $(BIN)/dem/aniso-dem $(CHART_RUN)/quasi-static $(CHART_OUT) 0.04 2 $^

# aniso beside DEMPLA (docs/validation.md, "DEM against DEMPLA"): DEMPLA's Dsphere_1800 in both
# codes, seven loadings to 20% (about 3 h on one core), DEMPLA without its rotational damping to 10%
# (20 min) and the rate pair to 2% (about 40 min);
# DEMPLA_REPO is a local copy of github.com/mrkuhn53/dempla (branch master):
#   make -C workflows chart-dem-dempla BIN=<build dir> DEMPLA_REPO=<path>
chart-dem-dempla:
	@test -n "$(DEMPLA_REPO)" || { echo "set DEMPLA_REPO to a local copy of github.com/mrkuhn53/dempla" >&2; exit 2; }
	mkdir -p $(CHART_RUN)/dempla $(CHART_RUN)/dempla-10pc $(CHART_RUN)/dempla-2pc $(CHART_OUT)
	../tests/dem/peer/dempla_biaxial.sh $(BIN) $(CHART_RUN)/dempla $(DEMPLA_REPO) 0.20 \
	  dempla_default aniso_default aniso_qs aniso_oval dempla_no_body aniso_body aniso_body_spin
	../tests/dem/peer/dempla_biaxial.sh $(BIN) $(CHART_RUN)/dempla-10pc $(DEMPLA_REPO) 0.10 dempla_no_spin_damping
	../tests/dem/peer/dempla_biaxial.sh $(BIN) $(CHART_RUN)/dempla-2pc $(DEMPLA_REPO) 0.02 \
	  dempla_default dempla_slow aniso_default aniso_slow
	$(PYTHON) studies/chart_dem_dempla.py $(CHART_RUN)/dempla/results,$(CHART_RUN)/dempla-10pc/results $(CHART_OUT) \
	  dem_dempla_spheres
	$(PYTHON) studies/chart_dem_dempla.py $(CHART_RUN)/dempla-2pc/results $(CHART_OUT) dem_dempla_spheres_rate

# The named loading behaviours (inertial, oval, quasi_static, and OVAL's increments) on 1000 spheres
# (demo seed 1) and 1000 ovoids of alpha 0.5 and 0.625 prepared by the paper configs (as the inertial
# behaviour consolidates), each loaded to 20%: about 1.5 h on two cores.
#   make -C workflows chart-dem-behaviours BIN=<build dir>
chart-dem-behaviours: $(CHART_RUN)/seed1/prepared.h5 $(CHART_RUN)/ovoids-0.5/prepared.h5
	test -f $(CHART_RUN)/ovoids-0.625/prepared.h5 || $(BIN)/dem/aniso-dem prepare \
	  --config configs/paper-ovoids-0.625.toml --set dem.particles.count=1000 --set dem.load.behaviour=inertial \
	  --set dem.output_dir=$(CHART_RUN)/ovoids-0.625
	mkdir -p $(CHART_RUN)/behaviours $(CHART_OUT)
	$(PYTHON) studies/load_behaviours.py $(BIN) $(CHART_RUN)/behaviours 0.20 spheres=configs/paper-spheres.toml:$(CHART_RUN)/seed1/prepared.h5 \
	  ovoids-0.5=configs/paper-ovoids-0.5.toml:$(CHART_RUN)/ovoids-0.5/prepared.h5 \
	  ovoids-0.625=configs/paper-ovoids-0.625.toml:$(CHART_RUN)/ovoids-0.625/prepared.h5
	$(PYTHON) studies/chart_dem_behaviours.py $(CHART_RUN)/behaviours/results $(CHART_OUT)

# The preparation as a lever (issue 45, item 4; docs/methods/dem.md, "The preparation study"):
# assemblies near e = 0.556 made in different ways (the compaction's friction, agitation, damping and
# rate, and frictionless-made assemblies stopped at the target), each loaded to 20% with its paper
# config (oval): 1000 spheres (three seeds for four of the ways) and ovoids of alpha 0.625 and 0.5.
# About 2.5 h on two cores (run two at once with make -j2 on the three groups).
#   make -C workflows chart-preparation-study BIN=<build dir>
PREP_STUDY = $(PYTHON) studies/preparation_study.py $(BIN) $(CHART_RUN)/preparation 0.20
SPHERES := configs/paper-spheres.toml
MU0_STOP := dem.material.friction_prepare=0,dem.prepare.compaction_stop_void_ratio
prep-study-spheres:
	$(PREP_STUDY) sph_paper=$(SPHERES) sph_mu0stop=$(SPHERES):$(MU0_STOP)=0.575 \
	  sph_agit005=$(SPHERES):dem.prepare.agitation_speed=0.05 sph_agit03=$(SPHERES):dem.prepare.agitation_speed=0.3 \
	  sph_mu01=$(SPHERES):dem.material.friction_prepare=0.1 sph_mu05=$(SPHERES):dem.material.friction_prepare=0.5 \
	  sph_damp0=$(SPHERES):dem.prepare.damping=0
	$(PREP_STUDY) sph_paper_s2=$(SPHERES):dem.seed=2 sph_mu0stop_s2=$(SPHERES):dem.seed=2,$(MU0_STOP)=0.565 \
	  sph_agit005_s2=$(SPHERES):dem.seed=2,dem.prepare.agitation_speed=0.05 \
	  sph_agit03_s2=$(SPHERES):dem.seed=2,dem.prepare.agitation_speed=0.3 \
	  sph_paper_s3=$(SPHERES):dem.seed=3 sph_mu0stop_s3=$(SPHERES):dem.seed=3,$(MU0_STOP)=0.565 \
	  sph_agit005_s3=$(SPHERES):dem.seed=3,dem.prepare.agitation_speed=0.05 \
	  sph_agit03_s3=$(SPHERES):dem.seed=3,dem.prepare.agitation_speed=0.3 \
	  sph_gd002=$(SPHERES):dem.prepare.global_damping=0.02 sph_slow=$(SPHERES):dem.prepare.inertial_number=1e-3
prep-study-ovoids-0.625:
	$(PREP_STUDY) o625_paper=configs/paper-ovoids-0.625.toml \
	  o625_mu0stop=configs/paper-ovoids-0.625.toml:$(MU0_STOP)=0.575 \
	  o625_gd01=configs/paper-ovoids-0.625.toml:dem.prepare.global_damping=0.1 \
	  o625_agit02=configs/paper-ovoids-0.625.toml:dem.prepare.agitation_speed=0.2 \
	  o625_spin6=configs/paper-ovoids-0.625.toml:dem.prepare.global_damping_spin_factor=6,dem.prepare.agitation_speed=0.3
prep-study-ovoids-0.5:
	$(PREP_STUDY) o5_paper=configs/paper-ovoids-0.5.toml o5_mu0stop=configs/paper-ovoids-0.5.toml:$(MU0_STOP)=0.575 \
	  o5_agit02=configs/paper-ovoids-0.5.toml:dem.prepare.agitation_speed=0.2
chart-preparation-study: prep-study-spheres prep-study-ovoids-0.625 prep-study-ovoids-0.5
	$(PYTHON) studies/chart_preparation_study.py $(CHART_RUN)/preparation $(CHART_OUT)

# aniso beside DEMPLA on ovoids: 1000 alpha = 0.625 ovoids prepared by the paper config (8 min),
# written as a DEMPLA D-file; each code loads it to 20% (DEMPLA about 30 min a run, aniso 3-25 min),
# then the damped loadings at a tenth of the rate (DEMPLA to 2%, aniso to 10%): about 4 h on one core.
#   make -C workflows chart-dem-dempla-ovoids BIN=<build dir> DEMPLA_REPO=<path>
chart-dem-dempla-ovoids:
	@test -n "$(DEMPLA_REPO)" || { echo "set DEMPLA_REPO to a local copy of github.com/mrkuhn53/dempla" >&2; exit 2; }
	mkdir -p $(CHART_RUN)/dempla-ovoids $(CHART_OUT)
	test -f $(CHART_RUN)/dempla-ovoids/prepared/prepared.h5 || $(BIN)/dem/aniso-dem prepare \
	  --config configs/paper-ovoids-0.625.toml --set dem.particles.count=1000 \
	  --set dem.output_dir=$(CHART_RUN)/dempla-ovoids/prepared
	START=$(abspath $(CHART_RUN))/dempla-ovoids/prepared/prepared.h5 ../tests/dem/peer/dempla_biaxial.sh $(BIN) \
	  $(CHART_RUN)/dempla-ovoids/work $(DEMPLA_REPO) 0.20 \
	  dempla_default dempla_no_body aniso_default aniso_body_spin aniso_halfwidth aniso_oval aniso_slow aniso_qs
	$(PYTHON) studies/chart_dem_dempla.py $(CHART_RUN)/dempla-ovoids/work/results $(CHART_OUT) dem_dempla_ovoids
	START=$(abspath $(CHART_RUN))/dempla-ovoids/prepared/prepared.h5 ../tests/dem/peer/dempla_biaxial.sh $(BIN) \
	  $(CHART_RUN)/dempla-ovoids/work-2pc $(DEMPLA_REPO) 0.02 dempla_slow
	START=$(abspath $(CHART_RUN))/dempla-ovoids/prepared/prepared.h5 ../tests/dem/peer/dempla_biaxial.sh $(BIN) \
	  $(CHART_RUN)/dempla-ovoids/work-10pc $(DEMPLA_REPO) 0.10 aniso_body_spin_slow
	rm -rf $(CHART_RUN)/dempla-ovoids/rate && mkdir -p $(CHART_RUN)/dempla-ovoids/rate
	cp $(foreach r,dempla_default aniso_body_spin aniso_default aniso_slow aniso_qs,$(CHART_RUN)/dempla-ovoids/work/results/$(r).csv) \
	  $(CHART_RUN)/dempla-ovoids/work-2pc/results/dempla_slow.csv \
	  $(CHART_RUN)/dempla-ovoids/work-10pc/results/aniso_body_spin_slow.csv $(CHART_RUN)/dempla-ovoids/rate/
	$(PYTHON) studies/chart_dem_dempla.py $(CHART_RUN)/dempla-ovoids/rate $(CHART_OUT) dem_dempla_ovoids_rate
	# A second realisation (seed 2), aniso alone, from its prepared state (halfwidth Hertz radius), to 10%.
	test -f $(CHART_RUN)/dempla-ovoids/seed2/prepared.h5 || $(BIN)/dem/aniso-dem prepare \
	  --config configs/paper-ovoids-0.625.toml --set dem.particles.count=1000 --set dem.seed=2 \
	  --set dem.output_dir=$(CHART_RUN)/dempla-ovoids/seed2
	$(PYTHON) studies/load_behaviours.py $(BIN) $(CHART_RUN)/dempla-ovoids/seed2 0.10 \
	  aniso=:$(CHART_RUN)/dempla-ovoids/seed2/prepared.h5 -- default:dem.load.inertial_number=1.2e-3 \
	  body_spin:dem.load.inertial_number=1.2e-3,dem.integration.global_damping=0.071,dem.integration.global_damping_spin_factor=6,dem.integration.damping=0 \
	  qs:dem.load.quasi_static=true,dem.load.increment=3e-5,dem.load.increment_tolerance=1e-3
	$(PYTHON) studies/chart_dem_dempla.py $(CHART_RUN)/dempla-ovoids/seed2/results $(CHART_OUT) dem_dempla_ovoids_seed2
