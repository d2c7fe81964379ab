// The browser suite's fragment shader (tests/js/glsl_runtime.html), after "#version" and probe.glsl:
// fragment (i, 0) shades point i of iblPoints with the runtime's shadePoint, as the C++ runtime's shadeCpu
// does. iblPoints holds 4 RGBA32F texels per point in column i: position + metallic, normal + perceptual
// roughness, view + ao, base colour. Outputs: diffuse + the local probes' alpha, specular.
uniform RuntimeParams iblParams;
uniform LocalProbe iblLocalProbes[IBL_MAX_LOCAL_PROBES];
uniform uint iblDistantLdOffset; // where each buffer starts in iblData (probe.glsl)
uniform uint iblDfgOffset;
uniform uint iblLocalLdOffset;
uniform highp sampler2D iblPoints;
layout(location = 0) out vec4 diffuseAndAlpha;
layout(location = 1) out vec4 specularOut;

void main() {
    int i = int(gl_FragCoord.x);
    vec4 a = texelFetch(iblPoints, ivec2(i, 0), 0);
    vec4 b = texelFetch(iblPoints, ivec2(i, 1), 0);
    vec4 c = texelFetch(iblPoints, ivec2(i, 2), 0);
    vec4 d = texelFetch(iblPoints, ivec2(i, 3), 0);
    ShadingPoint sp;
    sp.position = a.xyz;
    sp.metallic = a.w;
    sp.normal = b.xyz;
    sp.perceptualRoughness = b.w;
    sp.view = c.xyz;
    sp.ao = c.w;
    sp.baseColor = d.xyz;
    ShadeResult r = shadePoint(sp, iblParams, iblDistantLdOffset, iblDfgOffset, iblLocalProbes, iblLocalLdOffset);
    diffuseAndAlpha = vec4(r.diffuse, r.localAlpha);
    specularOut = vec4(r.specular, 0.0);
}
