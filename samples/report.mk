# Speed against error (scripts/speed_vs_error.py), included by samples/Makefile: for each sample
# scene and each of kdrender's samplers, the error against a converged reference at 1, 2, 4, ...
# REPORT_SPP samples per pixel, with cumulative render seconds, as a CSV per sampler and one
# log-log plot of relMSE against seconds with a line per sampler.
#   make -C samples BUILD=<build dir> OUT=<output dir> report
#     ->  $(OUT)/report/<scene>-<sampler>.csv and <scene>.png
# The reference (REPORT_REFERENCE_SPP samples, seed 1, default sampler; the series use seed 0) is
# rendered once, by the first sampler's series, and kept in $(OUT)/report until the scene or tree
# changes. Smaller settings for a quick look:
#   make -C samples report REPORT_SIZE=64 REPORT_SPP=64 REPORT_REFERENCE_SPP=1024
REPORT_SCENES ?= cornell-box cornell-bunny textured-scene bunnies clearcoat
REPORT_SAMPLERS ?= sobol independent
REPORT_SIZE ?= 256
REPORT_SPP ?= 256
REPORT_REFERENCE_SPP ?= 4096
REPORT_BOUNCES ?= 8
KDCOMPARE = $(BUILD)/tools/kdcompare/kdcompare
# Debian's matplotlib belongs to /usr/bin/python3.
SPEED_VS_ERROR = /usr/bin/python3 ../scripts/speed_vs_error.py

# kdrender options per scene (the camera where the scene file has none, the environment), as the
# demo renders them.
REPORT_VIEW_cornell-box = $(CORNELL_VIEW)
REPORT_VIEW_cornell-bunny = $(CORNELL_VIEW)
REPORT_VIEW_bunnies = $(BUNNIES_VIEW)
REPORT_VIEW_clearcoat = $(CLEARCOAT_VIEW)
REPORT_FIRST_SAMPLER = $(firstword $(REPORT_SAMPLERS))

.PHONY: report
report: $(foreach scene,$(REPORT_SCENES),$(OUT)/report/$(scene).png)

# One series rule per sampler; the later samplers wait for the first, whose run renders the
# shared reference.
define REPORT_SERIES
$$(OUT)/report/%-$(1).csv: $$(OUT)/%.kdscene $$(OUT)/%.kdtree $$(KDRENDER) $$(KDCOMPARE) ../scripts/speed_vs_error.py \
    | $(if $(filter $(1),$(REPORT_FIRST_SAMPLER)),,$$(OUT)/report/%-$(REPORT_FIRST_SAMPLER).csv)
	mkdir -p $$(@D)
	$$(SPEED_VS_ERROR) run $$(OUT)/$$*.kdscene $$(OUT)/$$*.kdtree --csv $$@ --sampler $(1) \
	  --width $$(REPORT_SIZE) --height $$(REPORT_SIZE) --max-spp $$(REPORT_SPP) --max-bounces $$(REPORT_BOUNCES) \
	  --reference-spp $$(REPORT_REFERENCE_SPP) --kdrender $$(KDRENDER) --kdcompare $$(KDCOMPARE) \
	  -- $$(REPORT_VIEW_$$*)
endef
$(foreach sampler,$(REPORT_SAMPLERS),$(eval $(call REPORT_SERIES,$(sampler))))

$(OUT)/report/%.png: $(foreach sampler,$(REPORT_SAMPLERS),$(OUT)/report/%-$(sampler).csv)
	$(SPEED_VS_ERROR) plot $^ -o $@ --title "$*: relMSE against render time ($(REPORT_SIZE)x$(REPORT_SIZE), $(REPORT_BOUNCES) bounces)"
