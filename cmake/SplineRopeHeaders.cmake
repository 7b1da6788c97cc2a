# SPDX-License-Identifier: MIT
# Which headers each library installs, in three classes (paths relative to the source root, which is
# also the include root: an installed header keeps its path under include/SplineRope/).
#
#   API      The public interface: what users include. Covered by the version promise in
#            CHANGELOG.md (semantic versioning of these headers' names and documented behaviour).
#   SUPPORT  Installed only because an API header includes it (a class holds one of its types by
#            value). Not API: its names may change in any release; do not include it yourself.
#            Each says so in its first comment.
#   INTERNAL Not installed: implementation modules of the library (narrowphase primitives, energy
#            kernels, quadrature rules, GL plumbing).
#
# Every header of a module directory must be in exactly one class; the install.header_classes test
# fails otherwise, so a new header is a deliberate decision. The same lists drive install(FILES) in
# rope/, bullet_bridge/ and render/, and the README's layout section describes them.

set(SPLINEROPE_ROPE_API_HEADERS
  rope/common/error.h
  rope/common/types.h
  rope/spline/knot_vector.h
  rope/spline/bspline_basis.h
  rope/spline/bspline_curve.h
  rope/spline/knot_insertion.h
  rope/spline/knot_removal.h
  rope/spline/curve_split.h
  rope/spline/curve_interpolation.h
  rope/spline/arc_length.h
  rope/spline/control_polygon.h
  rope/rod/rod_settings.h
  rope/rod/rod.h
  rope/rod/coupled_solve.h
  rope/rod/axial_force.h
  rope/tractrix/tractrix_settings.h
  rope/tractrix/tractrix_rope.h
  rope/tractrix/tractrix_segment.h
  rope/tractrix/length_angle.h
  rope/tractrix/polygon_adaptation.h
)
set(SPLINEROPE_ROPE_SUPPORT_HEADERS
  rope/common/gmres.h          # bullet_bridge/contact/body_contacts.h holds a solver
  rope/rod/banded_matrix.h     # Rod holds its step matrix
  rope/rod/pin_constraints.h   # Rod holds its constrained solver; Pin (Rod::pins()) is API
  rope/rod/rod_integrals.h     # Rod holds its integrals (Rod::integrals() is for diagnostics)
  rope/tractrix/length_correction.h  # TractrixRope holds its correction workspace
)
set(SPLINEROPE_ROPE_INTERNAL_HEADERS
  rope/common/fixed_vector.h
  rope/common/prefetch.h
  rope/spline/gauss_legendre.h
  rope/spline/point_validation.h
  rope/rod/adaptivity.h
  rope/rod/bending_energy.h
  rope/rod/insertion_relaxation.h
  rope/rod/stretching_energy.h
  rope/tractrix/tractrix_chain.h
)

set(SPLINEROPE_BULLET_BRIDGE_API_HEADERS
  bullet_bridge/rope_world.h
  bullet_bridge/rope_object.h
  bullet_bridge/rope_settings.h
  bullet_bridge/attachment.h
  bullet_bridge/winch.h
  bullet_bridge/contact_report.h
  bullet_bridge/rope_queries.h
  bullet_bridge/rope_debug_draw.h
  bullet_bridge/kinematic_rope.h
  bullet_bridge/kinematic_rope_settings.h
  bullet_bridge/find_contacts.h
  bullet_bridge/contact.h
  bullet_bridge/capsule.h
  bullet_bridge/capsule_proxies.h
  bullet_bridge/bullet_precision.h
  bullet_bridge/rope_warnings.h
  bullet_bridge/friction_combination.h
)
set(SPLINEROPE_BULLET_BRIDGE_SUPPORT_HEADERS
  bullet_bridge/contact/contact_response.h         # via attachment.h and rope_rope_contact.h
  bullet_bridge/contact/rope_rope_contact.h        # RopeWorld holds the rope-rope contact solver
  bullet_bridge/contact/kinematic_push.h           # KinematicRope holds its one-way contacts
  bullet_bridge/contact/body_contacts.h            # RopeObject holds its rope-body line contact
  bullet_bridge/contact/line_contact.h             # BodyContacts holds its sampler
  bullet_bridge/contact/friction_anchors.h         # BodyContacts holds the friction anchors
  bullet_bridge/contact/rope_stick_memory.h        # RopeRopeContacts holds the rope-rope stick state
  bullet_bridge/detail/radix_sort.h                # RopeRopeContacts holds its sort's keys
  bullet_bridge/collision_object/rope_shape.h      # the rope's compound shape, held by capsule_proxies.h
  bullet_bridge/collision_object/rope_dispatch.h   # RopeWorld holds the rope pairs' dispatch
)
set(SPLINEROPE_BULLET_BRIDGE_INTERNAL_HEADERS
  bullet_bridge/narrowphase/convex_support.h
  bullet_bridge/narrowphase/convex_contact.h
  bullet_bridge/narrowphase/concave_contact.h
  bullet_bridge/narrowphase/segment_convex_distance.h
  bullet_bridge/narrowphase/segment_segment_distance.h
  bullet_bridge/narrowphase/ray_capsule.h
  bullet_bridge/narrowphase/segment_triangle_distance.h
  bullet_bridge/contact/distributed_loads.h
  bullet_bridge/contact/axis_departure.h
  bullet_bridge/detail/bullet_math.h
  bullet_bridge/detail/body_state.h
  bullet_bridge/detail/world_membership.h
  bullet_bridge/detail/guarded_call.h
  bullet_bridge/detail/tree_pairs.h
  bullet_bridge/detail/self_pair_cache.h
  bullet_bridge/detail/rest_arc.h
  bullet_bridge/detail/side_thread.h
  bullet_bridge/detail/faster_of_two.h
  bullet_bridge/collision_object/capsule_dispatch.h
)

set(SPLINEROPE_RENDER_API_HEADERS
  render/renderer.h
  render/camera.h
  render/image.h
  render/scene.h
  render/mesh.h
  render/bounding_box.h
  render/colour.h
  render/world_extraction.h
  render/shape_mesh_cache.h
  render/shape_mesh.h
  render/rope_drawing.h
  render/tube_mesh.h
  render/polyline_mesh.h
  render/primitive_mesh.h
  render/png_writer.h
  render/video_writer.h
)
set(SPLINEROPE_RENDER_SUPPORT_HEADERS)
set(SPLINEROPE_RENDER_INTERNAL_HEADERS
  render/gl_context.h
  render/frame_filter.h
  render/fp_environment.h
)

# Installs the API and SUPPORT headers of one library (MODULE: ROPE, BULLET_BRIDGE or RENDER) under
# include/SplineRope/, keeping their paths, as part of the install component COMPONENT.
function(splinerope_install_headers module component)
  foreach(header IN LISTS SPLINEROPE_${module}_API_HEADERS SPLINEROPE_${module}_SUPPORT_HEADERS)
    get_filename_component(directory "${header}" DIRECTORY)
    install(FILES "${PROJECT_SOURCE_DIR}/${header}"
      DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/SplineRope/${directory}"
      COMPONENT ${component})
  endforeach()
endfunction()
