// SPDX-License-Identifier: MIT
#include "render/renderer.h"

#include <GL/osmesa.h>
#include <GL/glext.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "render/fp_environment.h"
#include "render/frame_filter.h"
#include "render/gl_context.h"
#include "rope/common/error.h"

namespace rope::render {

namespace {

// ---- Shaders (GLSL 3.30 core) ----

const char* const kSceneVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColour;
uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;
uniform mat4 uLightViewProjection;
uniform float uNormalOffset;
out vec3 vWorld;
out vec3 vNormal;
out vec3 vColour;
out vec3 vLight;
void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  vColour = aColour;
  // Normal-offset shadow lookup: sampling slightly outside the surface removes acne on slopes
  // without the light leaks a large constant bias causes. The light projection is orthographic.
  vLight = (uLightViewProjection * vec4(world.xyz + normalize(vNormal) * uNormalOffset, 1.0)).xyz * 0.5 + 0.5;
  gl_Position = uViewProjection * world;
}
)";

// Shared by the surface and ground shaders. Colours are squared into (approximately) linear light
// and square-rooted back: gamma 2 instead of 2.2 saves llvmpipe two pow() per pixel.
const char* const kCommonFragmentCode = R"(
uniform sampler2DShadow uShadowMap;
uniform int uShadows;
uniform float uShadowTexel;
uniform vec3 uToLight;
uniform vec3 uEye;
uniform vec3 uHazeColour;  // linear
uniform float uFogStart;
uniform float uFogEnd;
uniform float uAlpha;
out vec4 fragColour;

float shadowFactor(vec3 p) {
  if (uShadows == 0 || p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
  // Two bilinear comparison taps (8 texels): a soft penumbra. Each tap costs llvmpipe several ms
  // per 720p frame, and four looked no different at 1024 texels.
  float r = 1.2 * uShadowTexel;
  float s = texture(uShadowMap, vec3(p.xy + vec2(-1.0, -0.35) * r, p.z));
  s += texture(uShadowMap, vec3(p.xy + vec2(1.0, 0.35) * r, p.z));
  return 0.5 * s;
}

void finish(vec3 linearColour, vec3 world) {
  float haze = smoothstep(uFogStart, uFogEnd, length(uEye - world));
  fragColour = vec4(sqrt(clamp(mix(linearColour, uHazeColour, haze), 0.0, 1.0)), uAlpha);
}
)";

const char* const kSurfaceFragmentShader = R"(
in vec3 vWorld;
in vec3 vNormal;
in vec3 vColour;
in vec3 vLight;
uniform vec3 uColour;
uniform int uOverlay;
void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 base = uColour * vColour;
  base *= base;
  float ndl = max(dot(n, uToLight), 0.0);
  if (uOverlay != 0) {
    finish(base * (0.55 + 0.45 * ndl), vWorld);
    return;
  }
  float shadow = shadowFactor(vLight);
  vec3 ambient = mix(vec3(0.20, 0.18, 0.16), vec3(0.42, 0.47, 0.56), 0.5 + 0.5 * n.y);
  vec3 sun = vec3(1.00, 0.95, 0.86);
  vec3 h = normalize(uToLight + normalize(uEye - vWorld));
  float specular = 0.22 * pow(max(dot(n, h), 0.0), 40.0) * step(0.0, dot(n, uToLight));
  finish(base * (ambient + sun * ndl * shadow) + sun * specular * shadow, vWorld);
}
)";

const char* const kGroundVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uModel;
uniform mat4 uViewProjection;
uniform mat4 uLightViewProjection;
out vec3 vWorld;
out vec3 vLight;
void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorld = world.xyz;
  // Orthographic light: affine in the position, so interpolating it is exact.
  vLight = (uLightViewProjection * world).xyz * 0.5 + 0.5;
  gl_Position = uViewProjection * world;
}
)";

// The ground covers most of the image, so everything constant over a plane (its normal, the
// diffuse term, the grid axes) comes in as uniforms, and the per-pixel work (grid, shadow lookup,
// haze) is blended in display space: no conversion to linear light and back per pixel.
const char* const kGroundFragmentShader = R"(
in vec3 vWorld;
in vec3 vLight;
uniform vec3 uAxisU;       // grid directions in the plane, divided by the grid spacing
uniform vec3 uAxisV;
uniform vec3 uLit;         // display colour in full light
uniform vec3 uUnlit;       // display colour in shadow
uniform vec3 uHaze;        // display colour of the haze
uniform float uFogStart2;  // squared haze start distance
uniform float uFogScale2;  // 1 / (end^2 - start^2)
void main() {
  // Cell coordinates: the plane's grid directions were divided by the spacing on the CPU.
  vec2 minorCell = vec2(dot(vWorld, uAxisU), dot(vWorld, uAxisV));
  vec2 wMinor = fwidth(minorCell);
  // Inverse line width in cells, shared by both line sets (major lines are 5 cells apart and 1.5
  // times as wide), so the pixel needs two divisions rather than four.
  vec2 inverse = 1.0 / max(wMinor, vec2(1e-6));
  vec2 gMinor = abs(fract(minorCell - 0.5) - 0.5) * inverse;
  vec2 gMajor = abs(fract(minorCell * 0.2 - 0.5) - 0.5) * inverse * (1.0 / 0.3);
  // Lines fade out where cells shrink to a few pixels, so the grid never turns into moire towards
  // the horizon (linear ramps: cheaper than smoothstep, and invisible at this scale).
  float w = max(wMinor.x, wMinor.y);
  float minor = (1.0 - min(min(gMinor.x, gMinor.y), 1.0)) * clamp(1.25 - 5.0 * w, 0.0, 1.0);
  float major = (1.0 - min(min(gMajor.x, gMajor.y), 1.0)) * clamp(1.25 - w, 0.0, 1.0);
  float line = max(0.22 * minor, 0.4 * major);
  vec3 colour = mix(uUnlit, uLit, shadowFactor(vLight)) * (1.0 - line);
  // Haze on the squared distance: no square root per pixel.
  vec3 d = uEye - vWorld;
  float haze = clamp((dot(d, d) - uFogStart2) * uFogScale2, 0.0, 1.0);
  fragColour = vec4(mix(colour, uHaze, haze), uAlpha);
}
)";

const char* const kDepthVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uModel;
uniform mat4 uLightViewProjection;
void main() { gl_Position = uLightViewProjection * (uModel * vec4(aPosition, 1.0)); }
)";

const char* const kDepthFragmentShader = R"(#version 330 core
void main() {}
)";

// Sky: a band from the horizon line to the top of the image, at the far plane and drawn after the
// opaque geometry, so the depth test leaves only uncovered pixels to shade. Below the horizon the
// clear colour (the horizon colour) shows, which is also the haze colour the ground fades into.
const char* const kSkyVertexShader = R"(#version 330 core
uniform float uHorizonY;  // NDC y of the horizon
out float vElevation;
void main() {
  float bottom = clamp(uHorizonY, -1.0, 1.0);
  // Triangle-strip order: bottom-left, bottom-right, top-left, top-right.
  vec2 p = vec2(gl_VertexID == 1 || gl_VertexID == 3 ? 1.0 : -1.0, gl_VertexID >= 2 ? 1.0 : bottom);
  vElevation = p.y - uHorizonY;
  gl_Position = vec4(p, 1.0, 1.0);
}
)";

const char* const kSkyFragmentShader = R"(#version 330 core
in float vElevation;
uniform vec3 uHorizon;  // linear
uniform vec3 uZenith;   // linear
out vec4 fragColour;
void main() {
  fragColour = vec4(sqrt(mix(uHorizon, uZenith, smoothstep(0.0, 1.4, vElevation))), 0.0);
}
)";

GLuint compileShader(GLenum type, const char* source, const char* name) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("Renderer: compiling the ") + name + " shader failed: " + log);
  }
  return shader;
}

GLuint linkProgram(const char* vertexSource, const char* fragmentSource, const char* name) {
  const GLuint vertex = compileShader(GL_VERTEX_SHADER, vertexSource, name);
  GLuint fragment = 0;
  try {
    fragment = compileShader(GL_FRAGMENT_SHADER, fragmentSource, name);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw std::runtime_error(std::string("Renderer: linking the ") + name + " program failed: " + log);
  }
  return program;
}

void checkGl(const char* where) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    throw std::runtime_error(std::string("Renderer: OpenGL error 0x") + [error] {
      char text[16];
      std::snprintf(text, sizeof text, "%04x", error);
      return std::string(text);
    }() + " in " + where);
  }
}

Eigen::Matrix4d orthographic(double left, double right, double bottom, double top, double near, double far) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 0) = 2.0 / (right - left);
  m(1, 1) = 2.0 / (top - bottom);
  m(2, 2) = -2.0 / (far - near);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

Eigen::Matrix4d lookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
  Camera camera;
  camera.eye = eye;
  camera.target = target;
  camera.up = up;
  return camera.viewMatrix();
}

struct GpuMesh {
  std::weak_ptr<const Mesh> source;
  GLuint vao = 0;
  GLuint vertexBuffer = 0;
  GLuint indexBuffer = 0;
  GLsizei indexCount = 0;
};

// One draw: a mesh with a general affine placement (the automatic ground quad is scaled).
struct Draw {
  const GpuMesh* gpu;
  Eigen::Matrix4f model;
  Eigen::Matrix3f normalMatrix;  // inverse transpose of the model's linear part
  Rgb colour;
  Material material;
  Vec3 groundNormal;  // world normal, for Material::Ground
  Vec3 groundPoint;   // a world point on the ground plane, for Material::Ground
};

// A linked program and lookup of its uniforms by name (missing ones give -1, which GL ignores).
struct Program {
  GLuint id = 0;
  GLint at(const char* name) const { return glGetUniformLocation(id, name); }
};

const Vec3 kSkyAmbient(0.42, 0.47, 0.56);     // linear, from above
const Vec3 kBounceAmbient(0.20, 0.18, 0.16);  // linear, from below
const Vec3 kSun(1.00, 0.95, 0.86);            // linear

Eigen::Vector3f linear(const Rgb& c) { return c.cwiseProduct(c); }

}  // namespace

void RenderSettings::validate() const {
  auto requireRange = [](const char* parameter, int value, int minimum, int maximum) {
    if (value < minimum || value > maximum) {
      throw InvalidArgument(parameter, std::to_string(value),
                            "must be within [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]");
    }
  };
  requireRange("settings.width", width, 1, 8192);
  requireRange("settings.height", height, 1, 8192);
  if (samples != 1 && samples != 2 && samples != 4 && samples != 8) {
    throw InvalidArgument("settings.samples", std::to_string(samples), "must be 1, 2, 4 or 8");
  }
  requireRange("settings.shadowMapSize", shadowMapSize, 256, 8192);
  for (int i = 0; i < 3; ++i) requireFinite("settings.lightDirection", lightDirection[i]);
  if (!(lightDirection.norm() > 0.0)) throw InvalidArgument("settings.lightDirection", "(0, 0, 0)", "must be non-zero");
  requirePositive("settings.gridSpacing", gridSpacing);
  requireColour("settings.horizonColour", horizonColour);
  requireColour("settings.zenithColour", zenithColour);
}

struct Renderer::Impl {
  RenderSettings settings;
  GlContext context;
  Program surface, ground, depth, sky;
  GLuint emptyVao = 0;
  GLuint msaaFramebuffer = 0, msaaColour = 0, msaaDepth = 0;
  // frame: the single-sample image that is read back (the MSAA resolve target, or the render
  // target itself without MSAA).
  GLuint frameFramebuffer = 0, frameColour = 0, frameDepth = 0;
  GLuint shadowFramebuffer = 0, shadowTexture = 0;
  std::unordered_map<const Mesh*, GpuMesh> meshes;
  std::shared_ptr<const Mesh> groundQuad;  // the quad |x|, |z| <= 1 at y = 0, scaled per frame
  std::vector<std::uint8_t> rgba;
  std::size_t uploads = 0;

  explicit Impl(const RenderSettings& s) : settings(s), context(s.width, s.height) {}

  void createResources();
  void releaseResources();
  const GpuMesh& upload(const std::shared_ptr<const Mesh>& mesh);
  void releaseUnused();
  void render(const Scene& scene, const Camera& camera, Image& out);

  // What every pass of one frame needs.
  struct FrameView {
    Eigen::Matrix4d viewProjection;
    Vec3 toLight;             // unit, towards the light
    BoundingBox sceneBounds;  // of the scene's items (ground excluded); may be empty
    BoundingBox bounds;       // sceneBounds, or the origin for an empty scene
    double radius = 0.1;      // of bounds, at least 0.1 m
    double fogStart = 0.0, fogEnd = 0.0;  // m from the eye
  };
  struct ShadowMap {
    bool enabled = false;
    Eigen::Matrix4d lightViewProjection = Eigen::Matrix4d::Identity();
    float texel = 0.0f;         // one texel in shadow-map coordinates
    float normalOffset = 0.0f;  // m, the lookup's offset along the normal (against shadow acne)
  };
  // The steps of render(), in order.
  FrameView frameView(const Scene& scene, const Camera& camera) const;
  std::vector<Draw> drawList(const Scene& scene, const FrameView& view);
  ShadowMap renderShadowMap(const std::vector<Draw>& draws, const FrameView& view);
  void beginMainPass();
  void drawSurfaces(const std::vector<Draw>& draws, const FrameView& view, const ShadowMap& shadow,
                    const Camera& camera);
  void drawGrounds(const std::vector<Draw>& draws, const FrameView& view, const ShadowMap& shadow,
                   const Camera& camera);
  void drawSky(const Camera& camera, const FrameView& view);
  void drawOverlays(const std::vector<Draw>& draws);
  void readBack(Image& out);
  void useWithFrameUniforms(const Program& program, const FrameView& view, const ShadowMap& shadow,
                            const Camera& camera) const;
  void drawWithSurfaceProgram(const std::vector<Draw>& draws, Material material) const;

  static void requireComplete(const char* what) {
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error(std::string("Renderer: ") + what + " incomplete (status " + std::to_string(status) + ")");
    }
  }
  static void release(GpuMesh& gpu) {
    glDeleteVertexArrays(1, &gpu.vao);
    glDeleteBuffers(1, &gpu.vertexBuffer);
    glDeleteBuffers(1, &gpu.indexBuffer);
  }
};

void Renderer::Impl::createResources() {
  const std::string surfaceSource = std::string("#version 330 core\n") + kCommonFragmentCode + kSurfaceFragmentShader;
  const std::string groundSource = std::string("#version 330 core\n") + kCommonFragmentCode + kGroundFragmentShader;
  surface.id = linkProgram(kSceneVertexShader, surfaceSource.c_str(), "surface");
  ground.id = linkProgram(kGroundVertexShader, groundSource.c_str(), "ground");
  depth.id = linkProgram(kDepthVertexShader, kDepthFragmentShader, "shadow depth");
  sky.id = linkProgram(kSkyVertexShader, kSkyFragmentShader, "sky");
  glGenVertexArrays(1, &emptyVao);

  const int w = settings.width, h = settings.height;
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (settings.samples > maxSamples) {
    throw InvalidArgument("settings.samples", std::to_string(settings.samples),
                          "exceeds GL_MAX_SAMPLES = " + std::to_string(maxSamples));
  }
  if (settings.samples > 1) {
    glGenRenderbuffers(1, &msaaColour);
    glBindRenderbuffer(GL_RENDERBUFFER, msaaColour);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, settings.samples, GL_RGBA8, w, h);
    glGenRenderbuffers(1, &msaaDepth);
    glBindRenderbuffer(GL_RENDERBUFFER, msaaDepth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, settings.samples, GL_DEPTH_COMPONENT24, w, h);
    glGenFramebuffers(1, &msaaFramebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, msaaFramebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaaColour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaaDepth);
    requireComplete("multisample framebuffer");
  }
  glGenRenderbuffers(1, &frameColour);
  glBindRenderbuffer(GL_RENDERBUFFER, frameColour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  glGenFramebuffers(1, &frameFramebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, frameFramebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, frameColour);
  if (settings.samples == 1) {
    glGenRenderbuffers(1, &frameDepth);
    glBindRenderbuffer(GL_RENDERBUFFER, frameDepth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, frameDepth);
  }
  requireComplete("frame framebuffer");

  glGenTextures(1, &shadowTexture);
  glBindTexture(GL_TEXTURE_2D, shadowTexture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, settings.shadowMapSize, settings.shadowMapSize, 0,
               GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glGenFramebuffers(1, &shadowFramebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowTexture, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  requireComplete("shadow framebuffer");

  Mesh quad;
  const Vec3 up = Vec3::UnitY();
  const std::uint32_t first = quad.addVertex(Vec3(-1, 0, -1), up);
  quad.addVertex(Vec3(-1, 0, 1), up);
  quad.addVertex(Vec3(1, 0, 1), up);
  quad.addVertex(Vec3(1, 0, -1), up);
  quad.addTriangle(first, first + 1, first + 2);
  quad.addTriangle(first, first + 2, first + 3);
  groundQuad = std::make_shared<const Mesh>(std::move(quad));
  checkGl("creating the renderer's resources");
}

void Renderer::Impl::releaseResources() {
  for (auto& entry : meshes) release(entry.second);
  meshes.clear();
  const GLuint framebuffers[] = {msaaFramebuffer, frameFramebuffer, shadowFramebuffer};
  glDeleteFramebuffers(3, framebuffers);
  const GLuint renderbuffers[] = {msaaColour, msaaDepth, frameColour, frameDepth};
  glDeleteRenderbuffers(4, renderbuffers);
  glDeleteTextures(1, &shadowTexture);
  glDeleteVertexArrays(1, &emptyVao);
  for (const Program* program : {&surface, &ground, &depth, &sky}) glDeleteProgram(program->id);
}

const GpuMesh& Renderer::Impl::upload(const std::shared_ptr<const Mesh>& mesh) {
  auto found = meshes.find(mesh.get());
  // Same address but a different (expired) owner: the old mesh died and this is a new one.
  if (found != meshes.end() && found->second.source.lock() == mesh) return found->second;
  if (found != meshes.end()) {
    release(found->second);
    meshes.erase(found);
  }
  // Malformed index data would make llvmpipe read outside the vertex buffer: reject it here, once
  // per mesh, before anything reaches GL.
  if (mesh->indices.size() % 3 != 0) {
    throw InvalidArgument("mesh.indices.size()", std::to_string(mesh->indices.size()), "must be a multiple of 3");
  }
  for (std::size_t i = 0; i < mesh->indices.size(); ++i) {
    if (mesh->indices[i] >= mesh->vertices.size()) {
      throw InvalidArgument("mesh.indices[" + std::to_string(i) + "]", std::to_string(mesh->indices[i]),
                            "must be < vertices.size() = " + std::to_string(mesh->vertices.size()));
    }
  }
  GpuMesh gpu;
  gpu.source = mesh;
  gpu.indexCount = static_cast<GLsizei>(mesh->indices.size());
  glGenVertexArrays(1, &gpu.vao);
  glBindVertexArray(gpu.vao);
  glGenBuffers(1, &gpu.vertexBuffer);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.vertexBuffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh->vertices.size() * sizeof(Vertex)),
               mesh->vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &gpu.indexBuffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indexBuffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh->indices.size() * sizeof(std::uint32_t)),
               mesh->indices.data(), GL_STATIC_DRAW);
  const auto stride = static_cast<GLsizei>(sizeof(Vertex));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offsetof(Vertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offsetof(Vertex, normal)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offsetof(Vertex, colour)));
  glBindVertexArray(0);
  ++uploads;
  return meshes[mesh.get()] = gpu;
}

void Renderer::Impl::releaseUnused() {
  for (auto it = meshes.begin(); it != meshes.end();) {
    if (it->second.source.expired()) {
      release(it->second);
      it = meshes.erase(it);
    } else {
      ++it;
    }
  }
}

namespace {

// NDC height of the horizon (the image of horizontal directions at infinity), the lowest point of
// it across the image when the camera is rolled; +2 when the camera looks straight down (no sky
// in view), -2 straight up (all sky).
double horizonHeight(const Camera& camera, const Eigen::Matrix4d& viewProjection) {
  const Vec3 forward = (camera.target - camera.eye).normalized();
  Vec3 horizontal(forward.x(), 0.0, forward.z());
  if (horizontal.norm() < 1e-6) return forward.y() < 0.0 ? 2.0 : -2.0;
  horizontal.normalize();
  const Vec3 side(-horizontal.z(), 0.0, horizontal.x());
  double lowest = 2.0;
  for (double k : {-3.0, 0.0, 3.0}) {
    Eigen::Vector4d direction;
    direction << horizontal + k * side, 0.0;  // w = 0: a point at infinity
    const Eigen::Vector4d clip = viewProjection * direction;
    if (clip.w() > 1e-9) lowest = std::min(lowest, clip.y() / clip.w());
  }
  return lowest;
}

// Height where the shadows land: the lowest ground plane under the scene's centre, or the scene's
// own bottom.
double shadowReceiverHeight(const std::vector<Draw>& draws, const BoundingBox& bounds) {
  double receiverHeight = bounds.min.y();
  for (const Draw& draw : draws) {
    if (draw.material != Material::Ground || std::abs(draw.groundNormal.y()) < 0.1) continue;
    const Vec3& onPlane = draw.groundPoint;
    const Vec3 offset = bounds.center() - onPlane;
    const double height = onPlane.y() - (draw.groundNormal.x() * offset.x() + draw.groundNormal.z() * offset.z()) /
                                            draw.groundNormal.y();
    receiverHeight = std::min(receiverHeight, height);
  }
  return receiverHeight;
}

struct LightFrustum {
  Eigen::Matrix4d lightViewProjection;
  double extent;  // m, the larger side of the frustum's cross-section
};

// The orthographic light frustum that holds the scene's bounds and their shadows on the plane at
// receiverHeight, padded a little.
LightFrustum fitLightFrustum(const BoundingBox& bounds, double radius, const Vec3& toLight, double receiverHeight) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? bounds.max.x() : bounds.min.x(), (i & 2) ? bounds.max.y() : bounds.min.y(),
                      (i & 4) ? bounds.max.z() : bounds.min.z());
    points.push_back(corner);
    if (toLight.y() > 0.05) points.push_back(corner - toLight * ((corner.y() - receiverHeight) / toLight.y()));
  }
  const Vec3 center = bounds.center();
  const Vec3 up = std::abs(toLight.y()) < 0.99 ? Vec3::UnitY() : Vec3::UnitX();
  const Eigen::Matrix4d lightView = lookAt(center + toLight * (4.0 * radius), center, up);
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : points) {
    const Vec3 q = (lightView * p.homogeneous()).head<3>();
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const double pad = 0.02 * radius + 1e-3;
  lo -= Vec3::Constant(pad);
  hi += Vec3::Constant(pad);
  return {orthographic(lo.x(), hi.x(), lo.y(), hi.y(), -hi.z() - pad, -lo.z() + pad) * lightView,
          std::max(hi.x() - lo.x(), hi.y() - lo.y())};
}

}  // namespace

// One frame, in the order the GPU needs it: the per-frame quantities (frameView), the draw list
// (uploading meshes seen for the first time), the shadow map, the main pass (surfaces, ground, sky,
// overlays) and the read-back.
void Renderer::Impl::render(const Scene& scene, const Camera& camera, Image& out) {
  const FrameView view = frameView(scene, camera);
  const std::vector<Draw> draws = drawList(scene, view);
  const ShadowMap shadow = renderShadowMap(draws, view);
  beginMainPass();
  drawSurfaces(draws, view, shadow, camera);
  // Ground after the objects standing on it: the depth test then skips its hidden pixels.
  drawGrounds(draws, view, shadow, camera);
  drawSky(camera, view);
  drawOverlays(draws);
  glBindVertexArray(0);
  readBack(out);
}

Renderer::Impl::FrameView Renderer::Impl::frameView(const Scene& scene, const Camera& camera) const {
  FrameView view;
  const double aspect = static_cast<double>(settings.width) / settings.height;
  view.viewProjection = camera.projectionMatrix(aspect) * camera.viewMatrix();
  view.toLight = -settings.lightDirection.normalized();
  view.sceneBounds = scene.bounds();
  view.bounds = view.sceneBounds;
  if (view.bounds.empty()) view.bounds.extend(Vec3::Zero());
  view.radius = std::max(view.bounds.radius(), 0.1);
  // Haze from a few scene sizes away, complete well before the ground's edge.
  const double viewDistance = std::max((camera.target - camera.eye).norm(), view.radius);
  view.fogStart = 2.0 * viewDistance;
  view.fogEnd = 9.0 * viewDistance;
  return view;
}

std::vector<Draw> Renderer::Impl::drawList(const Scene& scene, const FrameView& view) {
  std::vector<Draw> draws;
  draws.reserve(scene.items.size() + 1);
  for (const DrawItem& item : scene.items) {
    if (item.mesh->empty()) continue;
    const GpuMesh& gpu = upload(item.mesh);
    const Eigen::Matrix3d linearPart = item.transform.linear();
    const auto& n = item.mesh->vertices.front().normal;
    const auto& p = item.mesh->vertices.front().position;
    draws.push_back(Draw{&gpu, item.transform.matrix().cast<float>(), linearPart.cast<float>(),
                         item.colour, item.material, (linearPart * Vec3(n[0], n[1], n[2])).normalized(),
                         item.transform * Vec3(p[0], p[1], p[2])});
  }
  if (settings.autoGround && !scene.hasGround()) {
    const BoundingBox& bounds = view.bounds;
    const double half = 1.5 * view.fogEnd + view.radius;
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    placement.translate(Vec3(bounds.center().x(), std::min(0.0, bounds.min.y()), bounds.center().z()));
    placement.scale(Vec3(half, 1.0, half));
    draws.push_back(Draw{&upload(groundQuad), placement.matrix().cast<float>(), Eigen::Matrix3f::Identity(),
                         Rgb(0.80f, 0.80f, 0.78f), Material::Ground, Vec3::UnitY(), placement.translation()});
  }
  return draws;
}

// An orthographic light frustum fitted to the casters and to where their shadows fall on the ground
// below them; no shadows for an empty scene or with settings.shadows off.
Renderer::Impl::ShadowMap Renderer::Impl::renderShadowMap(const std::vector<Draw>& draws, const FrameView& view) {
  ShadowMap shadow;
  shadow.enabled = settings.shadows && !view.sceneBounds.empty();
  if (!shadow.enabled) return shadow;
  const LightFrustum frustum =
      fitLightFrustum(view.bounds, view.radius, view.toLight, shadowReceiverHeight(draws, view.bounds));
  shadow.lightViewProjection = frustum.lightViewProjection;
  const double texelWorld = frustum.extent / settings.shadowMapSize;
  shadow.texel = 1.0f / static_cast<float>(settings.shadowMapSize);
  shadow.normalOffset = static_cast<float>(1.5 * texelWorld);

  glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer);
  glViewport(0, 0, settings.shadowMapSize, settings.shadowMapSize);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.0f);
  glUseProgram(depth.id);
  const Eigen::Matrix4f lvp = shadow.lightViewProjection.cast<float>();
  glUniformMatrix4fv(depth.at("uLightViewProjection"), 1, GL_FALSE, lvp.data());
  const GLint model = depth.at("uModel");
  for (const Draw& draw : draws) {
    if (draw.material != Material::Surface) continue;
    glUniformMatrix4fv(model, 1, GL_FALSE, draw.model.data());
    glBindVertexArray(draw.gpu->vao);
    glDrawElements(GL_TRIANGLES, draw.gpu->indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  return shadow;
}

void Renderer::Impl::beginMainPass() {
  glBindFramebuffer(GL_FRAMEBUFFER, settings.samples > 1 ? msaaFramebuffer : frameFramebuffer);
  glViewport(0, 0, settings.width, settings.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // two-sided: triangle meshes of unknown winding, open tubes
  // Alpha marks pixels with geometry edges for the anti-aliasing filter (frame_filter.h): 0 for
  // sky and ground, whose shaders anti-alias themselves, 1 for objects.
  glClearColor(settings.horizonColour.x(), settings.horizonColour.y(), settings.horizonColour.z(), 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, shadowTexture);
}

// Makes program current with the uniforms the surface and ground shaders share.
void Renderer::Impl::useWithFrameUniforms(const Program& program, const FrameView& view, const ShadowMap& shadow,
                                          const Camera& camera) const {
  const Eigen::Matrix4f vp = view.viewProjection.cast<float>();
  const Eigen::Matrix4f lvp = shadow.lightViewProjection.cast<float>();
  const Eigen::Vector3f toLight = view.toLight.cast<float>();
  const Eigen::Vector3f eye = camera.eye.cast<float>();
  const Eigen::Vector3f hazeColour = linear(settings.horizonColour);
  glUseProgram(program.id);
  glUniformMatrix4fv(program.at("uViewProjection"), 1, GL_FALSE, vp.data());
  glUniformMatrix4fv(program.at("uLightViewProjection"), 1, GL_FALSE, lvp.data());
  glUniform1i(program.at("uShadowMap"), 0);
  glUniform1i(program.at("uShadows"), shadow.enabled ? 1 : 0);
  glUniform1f(program.at("uShadowTexel"), shadow.texel);
  glUniform3fv(program.at("uToLight"), 1, toLight.data());
  glUniform3fv(program.at("uEye"), 1, eye.data());
  glUniform3fv(program.at("uHazeColour"), 1, hazeColour.data());
  glUniform1f(program.at("uFogStart"), static_cast<float>(view.fogStart));
  glUniform1f(program.at("uFogEnd"), static_cast<float>(view.fogEnd));
  glUniform1f(program.at("uAlpha"), 1.0f);
}

// Draws the items of one material with the surface program, which must be current.
void Renderer::Impl::drawWithSurfaceProgram(const std::vector<Draw>& draws, Material material) const {
  const GLint model = surface.at("uModel"), normal = surface.at("uNormalMatrix"), colour = surface.at("uColour");
  for (const Draw& draw : draws) {
    if (draw.material != material) continue;
    glUniformMatrix4fv(model, 1, GL_FALSE, draw.model.data());
    const Eigen::Matrix3f normalMatrix = draw.normalMatrix.inverse().transpose();
    glUniformMatrix3fv(normal, 1, GL_FALSE, normalMatrix.data());
    glUniform3fv(colour, 1, draw.colour.data());
    glBindVertexArray(draw.gpu->vao);
    glDrawElements(GL_TRIANGLES, draw.gpu->indexCount, GL_UNSIGNED_INT, nullptr);
  }
}

void Renderer::Impl::drawSurfaces(const std::vector<Draw>& draws, const FrameView& view, const ShadowMap& shadow,
                                  const Camera& camera) {
  useWithFrameUniforms(surface, view, shadow, camera);
  glUniform1f(surface.at("uNormalOffset"), shadow.normalOffset);
  glUniform1i(surface.at("uOverlay"), 0);
  drawWithSurfaceProgram(draws, Material::Surface);
}

// Everything constant over a ground plane (its lighting, its grid axes) is computed here, so the
// shader's per-pixel work is the grid, the shadow lookup and the haze.
void Renderer::Impl::drawGrounds(const std::vector<Draw>& draws, const FrameView& view, const ShadowMap& shadow,
                                 const Camera& camera) {
  useWithFrameUniforms(ground, view, shadow, camera);
  glUniform1f(ground.at("uAlpha"), 0.0f);
  glUniform1f(ground.at("uFogStart2"), static_cast<float>(view.fogStart * view.fogStart));
  glUniform1f(ground.at("uFogScale2"),
              static_cast<float>(1.0 / (view.fogEnd * view.fogEnd - view.fogStart * view.fogStart)));
  for (const Draw& draw : draws) {
    if (draw.material != Material::Ground) continue;
    const Vec3& n = draw.groundNormal;
    Eigen::Index axis = 0;
    n.cwiseAbs().minCoeff(&axis);
    const Vec3 u = n.cross(Vec3::Unit(axis)).normalized();
    const Eigen::Vector3f uCells = (u / settings.gridSpacing).cast<float>();
    const Eigen::Vector3f vCells = (n.cross(u).normalized() / settings.gridSpacing).cast<float>();
    const Eigen::Vector3f base = linear(draw.colour);
    const Vec3 ambient = kBounceAmbient + (kSkyAmbient - kBounceAmbient) * (0.5 + 0.5 * n.y());
    const Vec3 direct = kSun * std::max(n.dot(view.toLight), 0.0);
    const Eigen::Vector3f unlit = base.cwiseProduct(ambient.cast<float>());
    const Eigen::Vector3f lit = base.cwiseProduct((ambient + direct).cast<float>());
    glUniform3fv(ground.at("uAxisU"), 1, uCells.data());
    glUniform3fv(ground.at("uAxisV"), 1, vCells.data());
    const Eigen::Vector3f litDisplay = lit.cwiseSqrt(), unlitDisplay = unlit.cwiseSqrt();
    glUniform3fv(ground.at("uLit"), 1, litDisplay.data());
    glUniform3fv(ground.at("uUnlit"), 1, unlitDisplay.data());
    glUniform3fv(ground.at("uHaze"), 1, settings.horizonColour.data());
    glUniformMatrix4fv(ground.at("uModel"), 1, GL_FALSE, draw.model.data());
    glBindVertexArray(draw.gpu->vao);
    glDrawElements(GL_TRIANGLES, draw.gpu->indexCount, GL_UNSIGNED_INT, nullptr);
  }
}

// Sky band above the horizon, behind everything drawn so far.
void Renderer::Impl::drawSky(const Camera& camera, const FrameView& view) {
  const double horizon = horizonHeight(camera, view.viewProjection);
  if (horizon >= 1.0) return;
  glUseProgram(sky.id);
  const Eigen::Vector3f hazeColour = linear(settings.horizonColour);
  const Eigen::Vector3f zenith = linear(settings.zenithColour);
  glUniform1f(sky.at("uHorizonY"), static_cast<float>(horizon));
  glUniform3fv(sky.at("uHorizon"), 1, hazeColour.data());
  glUniform3fv(sky.at("uZenith"), 1, zenith.data());
  glDepthMask(GL_FALSE);
  glBindVertexArray(emptyVao);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glDepthMask(GL_TRUE);
}

// Overlays: solid where visible, then faintly through whatever hides them (x-ray), so a control
// polygon inside a thick rope still shows. The surface program keeps the frame's uniforms from
// drawSurfaces.
void Renderer::Impl::drawOverlays(const std::vector<Draw>& draws) {
  const bool hasOverlay = std::any_of(draws.begin(), draws.end(),
                                      [](const Draw& draw) { return draw.material == Material::Overlay; });
  if (!hasOverlay) return;
  glUseProgram(surface.id);
  glUniform1i(surface.at("uOverlay"), 1);
  drawWithSurfaceProgram(draws, Material::Overlay);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glUniform1f(surface.at("uAlpha"), 0.4f);
  drawWithSurfaceProgram(draws, Material::Overlay);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_BLEND);
}

// Resolves the multisample buffer, reads the frame back, releases meshes nothing holds any more and
// converts (and anti-aliases) the pixels into out.
void Renderer::Impl::readBack(Image& out) {
  const int w = settings.width, h = settings.height;
  if (settings.samples > 1) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, msaaFramebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, frameFramebuffer);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, frameFramebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  rgba.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  checkGl("rendering a frame");
  releaseUnused();

  convertFrame(rgba.data(), w, h, settings.postAntiAliasing, out);
}

Renderer::Renderer(const RenderSettings& settings) {
  settings.validate();
  FloatingPointGuard guard;
  impl_ = std::make_unique<Impl>(settings);
  try {
    impl_->createResources();
  } catch (...) {
    impl_->releaseResources();
    throw;
  }
}

Renderer::~Renderer() {
  if (!impl_) return;
  FloatingPointGuard guard;
  try {
    impl_->context.makeCurrent();
    impl_->releaseResources();
  } catch (const std::exception&) {
    // The context goes away below, and with it every GL object.
  }
}

void Renderer::render(const Scene& scene, const Camera& camera, Image& out) {
  camera.validate();
  FloatingPointGuard guard;
  impl_->context.makeCurrent();
  impl_->render(scene, camera, out);
}

Image Renderer::render(const Scene& scene, const Camera& camera) {
  Image image;
  render(scene, camera, image);
  return image;
}

Image Renderer::render(const Scene& scene) { return render(scene, frameScene(scene)); }

Camera Renderer::frameScene(const Scene& scene) const {
  const BoundingBox box = scene.bounds();
  if (box.empty()) return Camera{};
  return frameBoundingBox(box, static_cast<double>(impl_->settings.width) / impl_->settings.height);
}

const RenderSettings& Renderer::settings() const { return impl_->settings; }
std::string Renderer::glVersion() const { return impl_->context.version(); }
std::string Renderer::glRenderer() const { return impl_->context.rendererName(); }
std::size_t Renderer::gpuMeshCount() const { return impl_->meshes.size(); }
std::size_t Renderer::uploadCount() const { return impl_->uploads; }

}  // namespace rope::render
