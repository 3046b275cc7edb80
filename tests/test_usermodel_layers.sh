#!/usr/bin/env bash
# test_usermodel_layers.sh - user models reach the rest of the program through the registry's
# interface and the program cache only (issue 13): host/core/models.c knows nothing of
# host/core/usermodel.c (models_register/struct model_runtime instead), and no engine builds
# a program for a user model or opens its reference itself (host/core/programs.h does).
set -u
SRC=${SRC_DIR:?}
. "$(dirname "${BASH_SOURCE[0]}")/testlib.sh"

# the registry includes and calls nothing of usermodel.c
! grep -nE '#include "usermodel.h"|usermodel_' "$SRC/host/core/models.c" && ok \
    || bad "host/core/models.c uses usermodel.c"
# usermodel.c registers through the registry's interface
grep -q 'models_register(&um->info, &um->runtime)' "$SRC/host/core/usermodel.c" && ok \
    || bad "usermodel.c does not register through models_register"
# no engine builds a user model's program or reference, or asks which models are user models
# in order to build: they call programs_kernel/programs_program/programs_host
hits=$(grep -nE 'usermodel_build|usermodel_builds_|usermodel_reference_|clsession_build_user|USERMODEL_FLOAT_OPTIONS' \
    "$SRC"/host/measure/*/*.c "$SRC"/host/measure/*/*.h "$SRC"/host/results/*.c "$SRC"/host/results/*.h || true)
[ -z "$hits" ] && ok || bad "engines build user models themselves: $hits"
# nor asks whether a model is a user model to decide how to evaluate it: what a model sees
# (c only) and what its reference costs come from the registry (model_sees_only_c,
# model_eval_host_on_device); only gate.c, which loads the user models a gates file names,
# includes usermodel.h
hits=$(grep -lE '#include "usermodel.h"|usermodel_of' "$SRC"/host/measure/*/*.c "$SRC"/host/results/*.c | grep -v '/gate\.c$' || true)
[ -z "$hits" ] && ok || bad "engines that ask for user models themselves: $hits"
for f in accuracy/accuracy.c accuracy/field.c render/render_shade.c throughput/throughput.c; do
    grep -qE 'programs_(kernel|program|host)\(' "$SRC/host/measure/$f" && ok || bad "$f does not use the program cache"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
