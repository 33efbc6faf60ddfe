#ifndef STEPS
#define STEPS 3
#endif
#define RATE 1.5   /* growth per step */
#define LIMIT 3
#define ANGLE 30
