#version 330 core
// SPDX-License-Identifier: MIT
// Depth only: nothing to write but depth.
void main() {}
