/* shade.c — headlight shading of an AOV into an 8-bit image (shade.h).
 * Normals in an AOV face the viewer, so n · (towards the eye) is never
 * negative and no orientation of the input matters. Colours are linear and
 * encoded to sRGB on output. */
#include "shade.h"

#include <math.h>

static const double background = 0.2;   /* sRGB grey level of a miss */
static const double ambient = 0.12;
static const double diffuse = 0.78;
static const double specular = 0.25;
static const double shininess = 40.0;

static unsigned char srgb_byte(double linear)
{
    double c = linear <= 0.0 ? 0.0 : linear >= 1.0 ? 1.0 : linear;
    double s = c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    return (unsigned char)lround(255.0 * s);
}

void sc_shade_aov(const sc_aov *aov, const sc_scene *scene, sc_image *img)
{
    sc_image_alloc(img, aov->width, aov->height, 3);
    unsigned char grey = (unsigned char)lround(255.0 * background);
    for (int j = 0; j < aov->height; j++)
        for (int i = 0; i < aov->width; i++) {
            size_t px = (size_t)j * (size_t)aov->width + (size_t)i;
            unsigned char *out = &img->pixels[3 * px];
            int id = aov->surface[px];
            if (id < 0) {
                out[0] = out[1] = out[2] = grey;
                continue;
            }
            double dir[3];
            sc_camera_ray(&aov->camera, i + 0.5, j + 0.5, dir);
            const float *n = &aov->normal[3 * px];
            /* Light and view both come from the eye: the half vector is -dir. */
            double cosine = -(n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]);
            if (cosine < 0.0)
                cosine = 0.0;
            double color[3] = {0.8, 0.8, 0.8};
            if (scene && id < scene->nsurfaces)
                for (int k = 0; k < 3; k++)
                    color[k] = scene->surfaces[id].color[k];
            double highlight = specular * pow(cosine, shininess);
            for (int k = 0; k < 3; k++)
                out[k] = srgb_byte(color[k] * (ambient + diffuse * cosine) + highlight);
        }
}
