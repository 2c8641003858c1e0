/* refract_none.cl — the paths of a frame rendered without refraction: every pixel's identity path
 * (refraction_path.h), its exit direction the camera ray's, so a pixel that sees nothing shows the
 * environment there and a dielectric is shaded flat. One work item per pixel. */
#include "refraction_path.h"

#ifndef PATH_GROUP
#define PATH_GROUP 64
#endif

__kernel __attribute__((reqd_work_group_size(PATH_GROUP, 1, 1))) void identity_paths(
    RenderCamera cam, __global RefractionPath* paths) {
  const uint id = get_global_id(0);
  if (id >= cam.width * cam.height) return;
  paths[id] = rp_identity(rp_camera_direction(&cam, id % cam.width, id / cam.width));
}
