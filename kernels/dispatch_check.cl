// The dispatch helper's self-check over each grid shape; the work-items live in dispatch_check.h.
#include "dispatch_check.h"

__kernel void checkCubeStore(__global float* out, DispatchCheckParams params) {
    dispatchCheckStoreItem(cubeWorkItem(params.width), out, params);
}
__kernel void checkCubeAdd(__global float* out, DispatchCheckParams params,
                           __global const float* increments) {
    dispatchCheckAddItem(cubeWorkItem(params.width), out, params, increments);
}
__kernel void checkStridedCubeStore(__global float* out, DispatchCheckParams params) {
    dispatchCheckStoreItem(cubeWorkItemStrided(params.width), out, params);
}
__kernel void checkStridedCubeAdd(__global float* out, DispatchCheckParams params,
                                  __global const float* increments) {
    dispatchCheckAddItem(cubeWorkItemStrided(params.width), out, params, increments);
}
__kernel void checkImageStore(__global float* out, DispatchCheckParams params) {
    dispatchCheckStoreItem(imageWorkItem(params.width, params.height), out, params);
}
__kernel void checkImageAdd(__global float* out, DispatchCheckParams params,
                            __global const float* increments) {
    dispatchCheckAddItem(imageWorkItem(params.width, params.height), out, params, increments);
}
__kernel void checkListStore(__global float* out, DispatchCheckParams params) {
    dispatchCheckStoreItem(listWorkItem(params.width), out, params);
}
__kernel void checkListAdd(__global float* out, DispatchCheckParams params,
                           __global const float* increments) {
    dispatchCheckAddItem(listWorkItem(params.width), out, params, increments);
}
