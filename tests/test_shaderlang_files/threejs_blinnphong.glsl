/* brdfbench-model
 * name: threeblinn
 * function: lobe
 * reference: phongn
 */
#define PI_INV 0.3183098861837907
#define clamp01( v ) clamp( v, 0.0, 1.0 )

float F_Schlick( const in float f0, const in float f90, const in float cosVH ) {
    float w = exp2( ( -5.55473 * cosVH - 6.98316 ) * cosVH );
    return f0 * ( 1.0 - w ) + f90 * w;
}
vec3 F_Schlick( const in vec3 f0, const in float f90, const in float cosVH ) {
    float w = exp2( ( -5.55473 * cosVH - 6.98316 ) * cosVH );
    return f0 * ( 1.0 - w ) + f90 * w;
}
float G_Implicit() {
    return 0.25;
}
float D_Blinn( const in float s, const in float cosNH ) {
    return PI_INV * ( s * 0.5 + 1.0 ) * pow( cosNH, s );
}
vec3 BRDF_BlinnPhong( const in vec3 l, const in vec3 v, const in vec3 nrm, const in vec3 spec, const in float s ) {
    vec3 h = normalize( l + v );
    float cosNH = clamp01( dot( nrm, h ) );
    float cosVH = clamp01( dot( v, h ) );
    vec3 F = F_Schlick( spec, 1.0, cosVH );
    return F * ( G_Implicit() * D_Blinn( s, cosNH ) );
}
float lobe( float c, float n ) {
    vec3 N = vec3( 0.0, 0.0, 1.0 );
    vec3 H = vec3( sqrt( max( 1.0 - c * c, 0.0 ) ), 0.0, c );
    vec3 V = 2.0 * c * H - N;
    return BRDF_BlinnPhong( N, V, N, vec3( 1.0 ), n ).x;
}
