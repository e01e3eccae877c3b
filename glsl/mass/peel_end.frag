#version 330 core
// When peeling ends [paper 4, section 3.2]: the stencil test does the work (a pixel passes
// where the peel just drawn met two or more fragments); the occlusion query around each
// body's quad counts those pixels. Nothing is written.

void main()
{
}
