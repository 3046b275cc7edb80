# fp16.sh - bad-input rows of break, continue and switch in shader-language models
# (host/core/shader/shaderlang_emit.c): a break outside a loop or switch, a continue outside a loop, a
# float selector, a repeated or non-constant label, a label outside a switch: refused at the
# user's line and column with exit 2 before anything is compiled (a *.shader file shows
# brdfbench's own check, a .glsl file glslang's). Sourced by tests/test_cli_errors.sh (its `t`).
mkdir -p flow_in
wf() { printf '%s\n' "$2" >"flow_in/$1"; }
wf break.shader 'float f(float c, float n) { break; return c; }'
wf continue.shader 'float f(float c, float n) { switch (1) { case 1: continue; } return c; }'
wf continue.glsl 'float f(float c, float n) { if (c > 0.5) continue; return c; }'
wf fswitch.shader 'float f(float c, float n) { switch (c) { default: break; } return c; }'
wf dupcase.shader 'float f(float c, float n) { switch (2) { case 1: break; case 1: break; } return c; }'
t 2 "^brdfbench accuracy: flow_in/break.shader:1:29: 'break' outside a loop or switch$" accuracy --model-file flow_in/break.shader
t 2 "^brdfbench accuracy: flow_in/continue.shader:1:50: 'continue' outside a loop$" accuracy --model-file flow_in/continue.shader
t 2 "^brdfbench accuracy: flow_in/continue.glsl:1: continue statement only allowed in loops \(glslang, the GLSL reference compiler\)$" accuracy --model-file flow_in/continue.glsl
t 2 "^brdfbench accuracy: flow_in/fswitch.shader:1:37: switch on a float: the selector is an int$" accuracy --model-file flow_in/fswitch.shader
t 2 "^brdfbench accuracy: flow_in/dupcase.shader:1:57: case 1 appears twice in one switch$" accuracy --model-file flow_in/dupcase.shader
t 2 "^brdfbench accuracy: --model k:1:1: 'case' outside a switch$" accuracy --model 'k=case 1: return c;'
t 2 "^brdfbench accuracy: --model k:1:30: a case label is a constant integer$" accuracy --model 'k=int i = 2; switch (i) { case c: break; } return c;'
