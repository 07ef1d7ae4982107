// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The symmetric program's coefficients and cases in the asymmetric
// program of AEDC-TR-78-10, one definition used by diagnose, the start
// values and the tests: a symmetric coefficient's images in the asymmetric
// expansion (SymmetricImages) and a whole symmetric case as the asymmetric
// program's case (ToAsymmetric; its rates through angles.h).
//
// Example Usage:
//
//   Case body_axes = ToAsymmetric(LoadConfig("table6_motion.yaml"));

#ifndef FIT3DOF_MODEL_CONVERSION_H_
#define FIT3DOF_MODEL_CONVERSION_H_

#include <string>
#include <vector>

#include "fit3dof/angles.h"
#include "fit3dof/case.h"

namespace fit3dof {

// An asymmetric coefficient that a symmetric one becomes for an
// axisymmetric body: value = sign * symmetric value.
struct CoefficientImage {
  const char* symmetric;
  const char* asymmetric;
  double sign;
};

// Every image, e.g. Cm_alpha -> Cm_alpha (+1) and Cn_beta (-1), Cm_q ->
// Cm_q and Cn_r, the cubic terms -> alpha^3, alpha beta^2, ... terms,
// Magnus, roll, tunnel terms, offsets and the roll-interaction error.
const std::vector<CoefficientImage>& SymmetricImages();

// The symmetric coefficients without an exact image in the asymmetric
// expansion (the |delta| terms, Cm_q_beta2, Cm_r_alpha_beta,
// Cm_p_alpha_delta2, Cm_alphadot).
const std::vector<const char*>& SymmetricWithoutImage();

// The first image listed of symmetric coefficient `symmetric`, the one
// ToAsymmetric gives its value and free flag (Cm_alpha_delta2 -> Cm_alpha3);
// nullptr for a name with no image.
const CoefficientImage* FirstImage(const std::string& symmetric);

// A place a coefficient takes in a program: its position in the program's
// table and the factor its value is multiplied by there.
struct ImagePosition {
  int position;
  double factor;
};

// Where coefficient `name` of program `from` goes in program `to`: itself
// in the same program; every image of a symmetric term in the asymmetric
// program (Cm_alpha -> Cm_alpha x 1 and Cn_beta x -1); an asymmetric term
// that is a symmetric term's first image back to that term (Cm_p_beta ->
// Cm_p_alpha), and nothing for the other images (the symmetric program
// reads an axisymmetric body off its first images, as ToSymmetric does).
// Empty for a name the table of `from` does not hold, or that has no
// place in `to`.
std::vector<ImagePosition> ImagesIn(ModelKind to,
                                    ModelKind from,
                                    const std::string& name);

// The tie ToAsymmetric gives the asymmetric coefficient `name` (to the
// first image of the same symmetric term, e.g. Cn_beta: -1 x Cm_alpha);
// false for a first image and for a name no symmetric term maps to.
bool SymmetricTie(const std::string& name, ParameterTie* tie);

// The same motion in the asymmetric program (body axes, I_zx): every
// symmetric term mapped to its images, the first image listed taking its
// value and free flag and the others tied to it (case.h: Cn_beta follows
// -Cm_alpha, Cn_r follows Cm_q, ...), I_z = I_y.
// Throws InputError when the case uses a term without an image. Initial
// conditions are converted from Euler rates to body rates.
Case ToAsymmetric(const Case& c);

// The asymmetric case `a` back in the symmetric program when it describes
// an axisymmetric body as ToAsymmetric leaves one: I_z = I_y, each
// symmetric term's other images tied to its first as ToAsymmetric ties
// them, and every term without a symmetric counterpart (I_zx, Cn_beta
// apart from -Cm_alpha, ...) zero and fixed. The first image gives the
// symmetric term its value and flags; initial conditions are converted
// from body rates to Euler rates. Throws InputError naming the first term
// that is not so. diagnose uses it when the body asymmetry a step brought
// in is pruned again (the final model then reports Cm_p_alpha, not
// Cm_p_beta and Cn_p_alpha).
Case ToSymmetric(const Case& a);

}  // namespace fit3dof

#endif  // FIT3DOF_MODEL_CONVERSION_H_
