// What the G-buffer and forward passes' stages hand on per vertex (vertex -> [tessellation] ->
// [geometry] -> fragment): the members of the VertexData interface block, and a copy between
// blocks (interface blocks cannot be assigned whole).
#ifndef LGH_GBUFFER_VERTEX_GLSL
#define LGH_GBUFFER_VERTEX_GLSL

#define GBUFFER_VERTEX_MEMBERS                                                                   \
  vec3 worldPosition;                                                                            \
  vec3 normal;                                                                                   \
  vec4 tangent;                                                                                  \
  vec2 uv0;                                                                                      \
  vec2 uv1;                                                                                      \
  vec4 color;                                                                                    \
  vec2 sprite;        /* position inside a point's square, [-1, 1]^2; 0 for triangles, lines */  \
  vec3 basePosition;  /* before displacement mapping moved it */                                 \
  vec3 diffuseLight;  /* Gouraud / flat: the lights' diffuse sum for a unit diffuse colour */    \
  vec3 specularLight; /* and their specular sum */

#define GBUFFER_COPY_VERTEX(to, from)   \
  to.worldPosition = from.worldPosition; \
  to.normal = from.normal;               \
  to.tangent = from.tangent;             \
  to.uv0 = from.uv0;                     \
  to.uv1 = from.uv1;                     \
  to.color = from.color;                 \
  to.sprite = from.sprite;               \
  to.basePosition = from.basePosition;   \
  to.diffuseLight = from.diffuseLight;   \
  to.specularLight = from.specularLight;

#endif
