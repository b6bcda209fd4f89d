/* shade.h — a simple look for an AOV image: a headlight (light at the eye)
 * with diffuse and a little specular light on each surface's colour,
 * background dark grey. Used by the reference's PNG so that every image
 * of the project looks alike whatever renderer filled the AOV. */
#ifndef SC_SHADE_H
#define SC_SHADE_H

#include "aov.h"
#include "image.h"
#include "scene.h"

/* Fills a freshly allocated RGB image of the AOV's size. Surface colours
 * come from scene (NULL or an id outside it: light grey). */
void sc_shade_aov(const sc_aov *aov, const sc_scene *scene, sc_image *img);

#endif
