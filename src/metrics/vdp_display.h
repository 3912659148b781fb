// Display model of the perceptual metric (FovVideoVDP): photometry turns pixel values into the
// luminance the eye receives (cd/m²); geometry turns pixel positions into visual angles.
//
// Geometry is a property of the pixel (its pitch over the viewing distance), never of a named
// display's resolution: an image is measured at its own size. (The reference implementation's
// named displays stretch any image over the display's full resolution, so a 320×180 image on a
// "4K" display gets the 4K display's angular extent with 1/12 of its pixels per degree of
// content; fovrt's geometry cannot express that.) A flat screen is assumed, like the reference:
// pixels per degree grow away from the screen centre (VdpGeometry::ResolutionMagnification).
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace fovrt {

enum class VdpEotf {
    Srgb,      // display-encoded [0,1] values through the sRGB curve, scaled to [black, peak]
    Linear,    // linear relative [0,1] values scaled to [black, peak] (1 = display white)
    Absolute,  // values already in cd/m², clamped to [black, peak] (HDR input)
};

struct VdpPhotometry {
    double peak = 100.0;  // cd/m²
    double black = 0.1;   // cd/m², effective black including reflections
    VdpEotf eotf = VdpEotf::Srgb;

    float Luminance(float value) const;
};
// Effective black level of a display: peak/contrast plus ambient light reflected by the panel
// (E_ambient/π · k_refl, the reference's model with its default reflectivity 0.005).
double VdpBlackLevel(double peak, double contrast, double ambientLux = 0.0, double reflectivity = 0.005);

// Absolute luminance (cd/m²) of one frame: one channel, or RGB through Rec.709 luminance
// (core/math.h) after the EOTF of each channel.
Plane<float> VdpLuminance(const Plane<float>& frame, const VdpPhotometry& photometry);
Plane<float> VdpLuminance(const Plane<vec3>& frame, const VdpPhotometry& photometry);

// VdpLuminance of an image stored as integer codes (a PNG's; code c of a b-bit image is the
// value c / (2^b − 1)) by table lookup: the luminance of every code on one channel and on all
// three (a grey pixel), made once with VdpLuminance's own float operations, so a pixel looked up
// equals VdpLuminance of its value bit for bit.
class VdpCodeLuminance {
public:
    VdpCodeLuminance(const VdpPhotometry& photometry, int bits);  // bits: 8 or 16
    int bits() const { return bits_; }
    // A width × height image of `channels` codes per pixel (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA;
    // alpha ignored) into `out`, reusing its memory when it has that size; the codes' type is
    // uint8_t for 8 bits, uint16_t for 16.
    template <typename Code>
    void Image(const Code* codes, int width, int height, int channels, Plane<float>& out) const;

private:
    int bits_;
    std::vector<float> channel_, grey_;  // indexed by code
};

struct VdpGeometry {
    double tanPerPixel = 0.0;  // pixel pitch / viewing distance (tangent of one pixel's angle)

    // A pixel that subtends 1/ppd degrees at the screen centre.
    static VdpGeometry FromPixelsPerDegree(double pixelsPerDegree);
    // An image `widthPixels` wide spanning `fovDegrees` horizontally (a camera's or headset's FOV).
    static VdpGeometry FromHorizontalFov(int widthPixels, double fovDegrees);
    // The pixel of a `diagonalInches` monitor of displayWidth × displayHeight pixels seen from
    // `distanceMeters`.
    static VdpGeometry FromMonitor(int displayWidth, int displayHeight, double diagonalInches,
                                   double distanceMeters);

    double PixelsPerDegree() const;  // at the screen centre
    // Visual angle (degrees; x right, y up) of position (x, y) in a width × height grid that
    // covers an image of imageWidth × imageHeight pixels (a pyramid band covers the whole image
    // with fewer, larger pixels), centred on the image.
    glm::dvec2 ViewDirection(double x, double y, int width, int height, int imageWidth,
                            int imageHeight) const;
    // Pixels per degree at `angleFromCentreDegrees` relative to the centre (≥ 1 on a flat screen).
    double ResolutionMagnification(double angleFromCentreDegrees) const;
};

// A named display: photometry plus the geometry of its pixel.
struct VdpDisplay {
    std::string name;
    std::string description;
    VdpPhotometry photometry;
    VdpGeometry geometry;
};
const std::vector<VdpDisplay>& VdpDisplayProfiles();
// The profile called `name`; fovrt::Error listing the known names otherwise.
const VdpDisplay& FindVdpDisplay(const std::string& name);

}  // namespace fovrt
