// A 2D canvas of a size in CSS pixels, drawn at the device's pixel ratio (at most
// MAX_PIXEL_RATIO) so that its lines stay sharp on high-density screens. The panels and plots
// draw into `ctx` in CSS pixels; those that draw a new picture each time start with clear().
//
//   const canvas = new HiDpiCanvas( { width: 300, height: 170, ariaLabel: 'Dominance', className: 'sp-canvas' } );
//   drawDominance( canvas.ctx, data, canvas );      // { width, height } in CSS pixels
//   canvas.resize( 420 );                           // a new width, the same height

/** Device pixels per CSS pixel at most: sharper buys nothing visible and costs fill rate. */
export const MAX_PIXEL_RATIO = 2;

/** The device's pixel ratio for 2D canvases, at most MAX_PIXEL_RATIO. */
export function canvasPixelRatio( win = globalThis ) {

	return Math.min( MAX_PIXEL_RATIO, win.devicePixelRatio || 1 );

}

export class HiDpiCanvas {

	/**
	 * @param {{ width: number, height: number, ariaLabel?: string, className?: string,
	 *   document?: Document }} options the size in CSS pixels; the canvas is an image (role img)
	 *   named `ariaLabel`
	 */
	constructor( { width, height, ariaLabel = '', className = '', document = globalThis.document } ) {

		this.element = document.createElement( 'canvas' );
		this.element.className = className;
		this.element.setAttribute( 'role', 'img' );
		this.element.setAttribute( 'aria-label', ariaLabel );
		this.ratio = canvasPixelRatio();
		this.resize( width, height );

	}

	/**
	 * Size the canvas to `width` x `height` CSS pixels; its context then draws in them again
	 * (sizing a canvas resets its context). `ctx` is null where there is no 2D context.
	 */
	resize( width, height = this.height ) {

		this.width = width;
		this.height = height;
		this.element.style.width = `${ width }px`;
		this.element.style.height = `${ height }px`;
		this.element.width = Math.round( width * this.ratio );
		this.element.height = Math.round( height * this.ratio );
		this.ctx = this.element.getContext( '2d' );
		this.ctx?.setTransform( this.ratio, 0, 0, this.ratio, 0, 0 );

	}

	/** The context, ready for a new picture: in CSS pixels and empty; null without one. */
	clear() {

		const ctx = this.element.getContext( '2d' );
		if ( ! ctx ) return null;
		ctx.setTransform( this.ratio, 0, 0, this.ratio, 0, 0 );
		ctx.clearRect( 0, 0, this.width, this.height );
		return ctx;

	}

}
