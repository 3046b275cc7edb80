# fullbrdf.sh - bad inputs of the hemisphere sweep of full BRDFs (accuracy --reference, --axis,
# --param, --axis-points, --hemisphere-grid): each refused with exit 2 and one line naming the
# flag and what it accepts, before any device work.
t 2 "^brdfbench accuracy: --axis: '9x' is not NAME or NAME=MIN:MAX \(accepted: n, alpha, roughness, m" \
    accuracy --models ct-ggx --axis 9x
t 2 "^brdfbench accuracy: --axis: 'roughness=0.9:0.1': the range is MIN:MAX, two numbers with MIN < MAX" \
    accuracy --models ct-ggx --axis roughness=0.9:0.1
t 2 "^brdfbench accuracy: --axis: ct-ggx:F0=0.5 has no parameter 'F1' \(accepted: n, alpha, roughness, m, F0\)" \
    accuracy --models ct-ggx --axis F1
t 2 "^brdfbench accuracy: --axis: roughness=0.5:2 is out of range \(accepted: 0.037606 <= roughness <= 1\)" \
    accuracy --models ct-ggx --axis roughness=0.5:2
t 2 "^brdfbench accuracy: --axis: F0=0.5:2 is outside the declared range of F0 \(accepted: 0 to 1\)" \
    accuracy --models ct-ggx --axis F0=0.5:2
t 2 "^brdfbench accuracy: --axis applies to the hemisphere sweep of full BRDFs, and none is among the models" \
    accuracy --models fvol --axis roughness
t 2 "^brdfbench accuracy: --param: 'F0' is not NAME=VALUE with a finite number" \
    accuracy --models ct-ggx --param F0
t 2 "^brdfbench accuracy: --param: ct-ggx:F0=0.5 has no parameter 'Q' \(accepted: n, F0\)" \
    accuracy --models ct-ggx --param Q=1
t 2 "^brdfbench accuracy: --reference: .*nosuch" accuracy --models ct-ggx --reference nosuch
t 2 "^brdfbench accuracy: --hemisphere-grid: 2x2x2 is out of range \(accepted: each of theta_h, theta_d, phi_d cells in \[4, 2048\]\)" \
    accuracy --models ct-ggx --hemisphere-grid 2x2x2
t 2 "^brdfbench accuracy: --hemisphere-grid: 'abc' is not NHxNDxNP" accuracy --models ct-ggx --hemisphere-grid abc
t 2 "^brdfbench accuracy: --axis-points" accuracy --models ct-ggx --axis-points 0
# (a user lobe model as the reference of a lobe model is measured: tests/test_reference_lobe.sh)
t 2 "^brdfbench accuracy: --hemisphere-grid: 1024x1024x1024 cells x 8 axis values is 8.59e\+09 grid points \(accepted: at most 5e\+08" \
    accuracy --models ct-ggx --hemisphere-grid 1024x1024x1024
