#version 330 core
// Pass 0 of paper 4, section 5.2: render the fluid surface, keeping only its depth (T_dw).
void main()
{
}
