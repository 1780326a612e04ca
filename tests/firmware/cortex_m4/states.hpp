// The fixed inputs of the Cortex-M4 test, shared by the firmware (float) and the host reference
// (double): the host converts these float values exactly, so the two compute the same
// mathematical function and differ only by the float evaluation on the target.
#ifndef MODELGEN_CORTEX_M4_STATES_HPP_
#define MODELGEN_CORTEX_M4_STATES_HPP_

namespace cortex_m4_test {

constexpr int kJoints = 6;
constexpr int kStates = 5;
constexpr int kBase = 61;

// TX-40 states within robots/tx40.yaml's limits (q within the joint ranges, |dq| within the
// velocity limits): at rest at q = 0; moving in both directions; near the range ends with
// velocities close to their limits; some joints at zero velocity (Coulomb sign 0); wrist
// joints turning against each other (the 5-6 coupling).
const float kQ[kStates][kJoints] = {
    {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {0.5f, -0.8f, 1.2f, -1.5f, 0.9f, 2.0f},
    {-2.5f, 1.7f, -2.0f, 3.5f, -1.8f, -4.0f},
    {3.0f, -2.1f, 0.3f, 4.6f, 2.2f, 0.0f},
    {1.2f, 0.4f, -0.6f, -0.3f, -1.0f, 1.57f},
};
const float kDq[kStates][kJoints] = {
    {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {1.0f, -0.5f, 2.0f, -3.0f, 1.5f, 4.0f},
    {-4.5f, 4.0f, -6.5f, 6.0f, -5.0f, -11.0f},
    {0.0f, 0.2f, 0.0f, -0.1f, 0.0f, 0.05f},
    {3.0f, -2.5f, 1.0f, 5.0f, -2.0f, 10.0f},
};
const float kDdq[kStates][kJoints] = {
    {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {2.0f, -3.0f, 4.0f, 5.0f, -6.0f, 8.0f},
    {-10.0f, 8.0f, -12.0f, 15.0f, -9.0f, 20.0f},
    {0.5f, -0.5f, 0.25f, 0.0f, 1.0f, -1.0f},
    {-4.0f, 6.0f, -2.0f, -8.0f, 3.0f, -15.0f},
};

// Base parameters in the order of kBaseParamNames (generated/tx40/tx40.cpp): the TX-40 values
// of Gautier & Briot, Table II, Case 2 (IDIM-WLS); a parameter Case 2 cancels takes its Case 4
// value, else its Case 3 value; offsets and Iam6 are the description's known values; the
// parameters the paper never estimates are 0.005, so that every term of the model counts.
const float kBeta[kBase] = {
    1.27f,     // ZZ1R
    6.90f,     // Fv1
    6.72f,     // Fc1
    0.392f,    // OFF1
    -0.484f,   // XX2R
    -0.106f,   // XY2 (Case 3)
    -0.145f,   // XZ2R
    0.005f,    // YZ2
    1.06f,     // ZZ2R
    2.21f,     // MX2R
    0.005f,    // MY2
    4.45f,     // Fv2
    7.87f,     // Fc2
    1.37f,     // OFF2
    0.0949f,   // XX3R
    0.005f,    // XY3
    0.093f,    // XZ3 (Case 3)
    0.225f,    // YZ3 (Case 3)
    0.146f,    // ZZ3R
    0.005f,    // MX3
    -0.607f,   // MY3R
    0.0874f,   // Ia3
    1.60f,     // Fv3
    6.30f,     // Fc3
    0.326f,    // OFF3
    0.005f,    // XX4R
    -0.1f,     // XY4 (Case 3)
    0.005f,    // XZ4
    0.0588f,   // YZ4 (Case 3)
    0.0372f,   // ZZ4R (Case 4)
    -0.0427f,  // MX4 (Case 4)
    0.005f,    // MY4R
    0.0351f,   // Ia4
    0.851f,    // Fv4
    2.55f,     // Fc4
    -0.102f,   // OFF4
    0.005f,    // XX5R
    0.005f,    // XY5
    0.005f,    // XZ5
    0.0561f,   // YZ5 (Case 3)
    0.005f,    // ZZ5R
    0.005f,    // MX5
    0.005f,    // MY5R
    0.0416f,   // Ia5
    1.56f,     // Fv5
    2.71f,     // Fc5
    -0.0288f,  // OFF5
    0.005f,    // XX6R
    0.0182f,   // XY6R (Case 3)
    -0.00254f, // XZ6R (Case 4)
    0.005f,    // YZ6R
    -0.026f,   // ZZ6R (Case 3)
    -0.0253f,  // MX6R (Case 4)
    0.0547f,   // MY6R (Case 3)
    0.0109f,   // Ia6
    0.513f,    // Fv6
    1.83f,     // Fc6
    0.127f,    // OFF6
    0.00964f,  // Iam6
    0.492f,    // Fvm6
    1.53f,     // Fcm6
};

}  // namespace cortex_m4_test

#endif
