# shader.sh - bad-input rows of the shader-language models (host/core/shader/shaderlang*.c): what a
# shader cannot do is refused at parse, at the user's file, line and column, with exit 2, before
# anything is compiled or run (in a .glsl/.hlsl file, what brdfbench's parser accepts is then
# checked by glslang, the reference compiler, whose message it prints; a file of another name,
# *.shader here, shows brdfbench's own check); the preprocessor's refusals; -D's form and place; translation
# bounded. Sourced by tests/test_cli_errors.sh (its `t` helper; the working folder is its $T).
mkdir -p shader_in
w() { printf '%s\n' "$2" >"shader_in/$1"; }
w ptr_decl.glsl 'float f(float c, float n) { float *p; return c; }'
w ptr_deref.glsl 'float f(float c, float n) { return c + *(float*)8; }'
w ptr_addr.hlsl 'float f(float c, float n) { float x = c; return x + (&x)[0]; }'
w ptr_param.glsl 'float g(float *p) { return 1.0; } float f(float c, float n) { return c; }'
w asm.glsl 'float f(float c, float n) { asm("nop"); return c; }'
w volatile.hlsl 'float f(float c, float n) { volatile float x = c; return x; }'
w printf.glsl 'float f(float c, float n) { printf(1); return c; }'
w printf.shader 'float f(float c, float n) { printf(1); return c; }'
w string.glsl 'float f(float c, float n) { return c + "a"; }'
w clcall.hlsl 'float f(float c, float n) { return native_powr(c, n); }'
w clcall.shader 'float f(float c, float n) { return native_powr(c, n); }'
w dialect.glsl 'float f(float c, float n) { return saturate(c); }'
w include.glsl '#include "other.glsl"'
w error.glsl '#error not for this target'
w noendif.glsl '#if 1'
w ok.glsl 'float ok(float c, float n) { return c; }'
printf 'float f(float c, float n) {\n    float s = 0.0;\n    for (int i = 0; i < 256; i++) {\n        for (int j = 0; j < 256; j++) {\n            s += c;\n        }\n    }\n    return s;\n}\n' >shader_in/unroll.glsl
printf '/* brdfbench-model\n * name: dd\n * define: 1X\n */\nfloat dd(float c, float n) { return c; }\n' >shader_in/define_key.glsl

t 2 "^brdfbench accuracy: shader_in/ptr_decl.glsl:1:35: a pointer declaration: pointers are not accepted in a model$" accuracy --model-file shader_in/ptr_decl.glsl
t 2 "^brdfbench accuracy: shader_in/ptr_deref.glsl:1:40: '\*' before a value reads through a pointer" accuracy --model-file shader_in/ptr_deref.glsl
t 2 "^brdfbench accuracy: shader_in/ptr_addr.hlsl:1:54: '&' takes an address" accuracy --model-file shader_in/ptr_addr.hlsl
t 2 "^brdfbench accuracy: shader_in/ptr_param.glsl:1:15: a pointer parameter: pointers are not accepted" accuracy --model-file shader_in/ptr_param.glsl
t 2 "^brdfbench accuracy: shader_in/asm.glsl:1:29: inline assembly is not accepted in a model$" accuracy --model-file shader_in/asm.glsl
t 2 "^brdfbench accuracy: shader_in/volatile.hlsl:1:29: volatile is not accepted in a model" accuracy --model-file shader_in/volatile.hlsl
t 2 "^brdfbench accuracy: shader_in/printf.glsl:1:29: 'printf': no matching overloaded function found \(glslang, the GLSL reference compiler\)$" accuracy --model-file shader_in/printf.glsl
t 2 "^brdfbench accuracy: shader_in/printf.shader:1:29: use of undeclared function 'printf' \(a model calls only its own functions and the math built-ins" accuracy --model-file shader_in/printf.shader
t 2 "^brdfbench accuracy: shader_in/string.glsl:1:40: a string or character literal: a model has none" accuracy --model-file shader_in/string.glsl
t 2 "^brdfbench accuracy: shader_in/clcall.hlsl:1:36: 'native_powr': no matching overloaded function found \(glslang, the HLSL reference compiler\)$" accuracy --model-file shader_in/clcall.hlsl
t 2 "^brdfbench accuracy: shader_in/clcall.shader:1:36: use of undeclared function 'native_powr'" accuracy --model-file shader_in/clcall.shader
t 2 "^brdfbench accuracy: shader_in/dialect.glsl:1:36: 'saturate': no matching overloaded function found \(glslang, the GLSL reference compiler\)$" accuracy --model-file shader_in/dialect.glsl
t 2 "^brdfbench accuracy: shader_in/include.glsl:1:1: #include is not accepted: a model file reads no other file$" accuracy --model-file shader_in/include.glsl
t 2 "^brdfbench accuracy: shader_in/error.glsl:1: #error: not for this target \(glslang's preprocessor\)$" accuracy --model-file shader_in/error.glsl
t 2 "^brdfbench accuracy: shader_in/noendif.glsl:2: missing #endif \(glslang's preprocessor\)$" accuracy --model-file shader_in/noendif.glsl
t 2 "^brdfbench accuracy: shader_in/unroll.glsl:4:9: the loops unroll to more than 8192 iterations in all" accuracy --model-file shader_in/unroll.glsl
t 2 "^brdfbench accuracy: shader_in/define_key.glsl:3: define: '1X': expected NAME or NAME=VALUE" accuracy --model-file shader_in/define_key.glsl
t 2 "^brdfbench accuracy: -D '1X': expected NAME or NAME=VALUE with NAME an identifier of 1 to 48 characters" accuracy -D 1X --model-file shader_in/define_key.glsl
t 2 "^brdfbench accuracy: -D X: given after --model-file shader_in/ok.glsl; put -D before" accuracy --model-file shader_in/ok.glsl -D X
t 2 "^brdfbench throughput: -D 'X=': the value must have 1 to" throughput -D X= --model-file shader_in/unroll.glsl
# --model texts: a pointer construct is refused by the shader-language parser for good, not
# compiled as OpenCL C (the first ran and wrote its outputs before)
t 2 "^brdfbench accuracy: --model z:1:5: '\*' before a value reads through a pointer: pointers are not accepted in a model$" accuracy --model 'z=c + *(float*)8' --n-max 3 --samples 16 --out shader_ze
t 2 "^brdfbench accuracy: --model z:1:5: sizeof is not accepted in a model" accuracy --model 'z=c + sizeof(c)' --n-max 3 --samples 16 --out shader_ze
t 2 "^brdfbench accuracy: --model z:1:2: '&' takes an address" accuracy --model 'z=(&c)[0]' --n-max 3 --samples 16 --out shader_ze
